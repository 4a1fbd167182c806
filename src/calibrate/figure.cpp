#include "calibrate/figure.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace pagecache::calibrate {

Figure figure(const Rate& r, std::string how) {
  if (r.bytes <= 0 || r.seconds <= 0.0) return Figure{0.0, how + ": nothing measured (interrupted?)", false};
  const double v = r.per_second();
  return Figure{v, fmt::format("{} ({} in {:.2f} s)", how, size_text(r.bytes), r.seconds), true, 0.0, v, v};
}

Figure repeated(int repeat, const std::function<Rate(int)>& once, const std::string& how) {
  std::vector<Rate> rates;
  for (int i = 0; i < repeat; ++i) {
    if (stop_requested()) break;
    rates.push_back(once(i));
  }
  if (rates.size() == 1) return figure(rates.front(), how);
  std::vector<double> values;
  for (const Rate& r : rates) {
    if (r.bytes <= 0 || r.seconds <= 0.0) return Figure{0.0, how + ": nothing measured (interrupted?)", false};
    values.push_back(r.per_second());
  }
  if (values.empty()) return Figure{0.0, how + ": nothing measured (interrupted?)", false};
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::string each;
  for (const double v : values) each += fmt::format("{}{:.0f}", each.empty() ? "" : ", ", v / 1e6);
  const double spread = (sorted.back() - sorted.front()) / median * 100.0;
  return Figure{median, fmt::format("{}: median of {} ({} MB/s; spread {:.0f} %)", how, values.size(), each, spread), true, spread, sorted.front(),
                sorted.back()};
}

}  // namespace pagecache::calibrate
