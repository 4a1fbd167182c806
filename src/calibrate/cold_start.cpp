#include "calibrate/cold_start.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/system_info.hpp"

#include <chrono>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <unistd.h>

namespace pagecache::calibrate {

bool drop_all_caches() {
  ::sync();
  std::ofstream out("/proc/sys/vm/drop_caches");
  out << "3\n";
  out.flush();
  return static_cast<bool>(out);
}

bool wait_for_reporting(double limit) {
  std::int64_t before = reported_free_bytes();
  if (before < 0) return false;
  const auto started = std::chrono::steady_clock::now();
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    if (stop_requested()) throw std::runtime_error("interrupted: the files made so far are removed");
    const std::int64_t now = reported_free_bytes();
    if (now == before) return true;
    before = now;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >= limit) return false;
  }
}

}  // namespace pagecache::calibrate
