#include "calibrate/real_run.hpp"

#include "calibrate/cold_start.hpp"
#include "calibrate/measure.hpp"
#include "calibrate/scratch.hpp"
#include "calibrate/system_info.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <latch>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <tuple>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::calibrate {

namespace {

using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& file) {
  throw std::system_error(errno, std::generic_category(), fmt::format("{} '{}'", what, file.string()));
}

void check_stopped() {
  if (stop_requested()) throw std::runtime_error("interrupted: the files made so far are removed");
}

double thread_cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// CPU-bound work for `seconds` of this thread's CPU time (a core shared with others takes
// longer, as a task's computation does).
void compute(double seconds) {
  const double end = thread_cpu_seconds() + seconds;
  volatile double x = 1.0;
  while (thread_cpu_seconds() < end && !stop_requested()) {
    for (int i = 0; i < 20000; ++i) x = x * 1.0000001 + 1e-9;
  }
}

void write_all(int fd, const char* data, std::int64_t size, std::int64_t chunk, const std::filesystem::path& file) {
  for (std::int64_t done = 0; done < size;) {
    check_stopped();
    const auto n = ::write(fd, data + done, static_cast<std::size_t>(std::min(chunk, size - done)));
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write", file);
    }
    done += n;
  }
}

// A file of `size` bytes written and synced: a pipeline's input.
void make_input(const std::filesystem::path& file, std::int64_t size) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) fail("cannot make", file);
  std::vector<char> block(static_cast<std::size_t>(std::min<std::int64_t>(size, 16 << 20)), 'x');
  try {
    for (std::int64_t done = 0; done < size; done += static_cast<std::int64_t>(block.size())) {
      write_all(fd, block.data(), std::min(static_cast<std::int64_t>(block.size()), size - done), static_cast<std::int64_t>(block.size()), file);
    }
    if (::fsync(fd) != 0) fail("cannot sync", file);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

void drop_file(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
  ::close(fd);
}

MemorySample sample(double time) {
  const std::string m = read_meminfo();
  return MemorySample{time, meminfo_bytes(m, "MemFree"), meminfo_bytes(m, "Cached"), meminfo_bytes(m, "Dirty"), meminfo_bytes(m, "Writeback")};
}

// One pipeline: task k reads file k whole into a new buffer, computes, writes file k + 1.
std::vector<RealPhase> pipeline(const RealCase& spec, const Scratch& scratch, int p, Clock::time_point start) {
  std::vector<RealPhase> phases;
  const auto now = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const auto name = [&](int k) { return scratch.file(fmt::format("p{}_file_{}", p, k)); };
  for (int k = 1; k <= spec.tasks; ++k) {
    check_stopped();
    const std::filesystem::path in = name(k);
    const std::filesystem::path out = name(k + 1);
    double t = now();
    const int fd = ::open(in.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail("cannot open", in);
    struct stat st{};
    ::fstat(fd, &st);
    const auto size = static_cast<std::int64_t>(st.st_size);
    void* memory = ::mmap(nullptr, static_cast<std::size_t>(std::max<std::int64_t>(size, 1)), PROT_READ | PROT_WRITE,
                          MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (memory == MAP_FAILED) {
      ::close(fd);
      throw std::bad_alloc();
    }
    char* buffer = static_cast<char*>(memory);
    const auto release = [&] { ::munmap(memory, static_cast<std::size_t>(std::max<std::int64_t>(size, 1))); };
    try {
      for (std::int64_t done = 0; done < size;) {
        check_stopped();
        const auto n = ::read(fd, buffer + done, static_cast<std::size_t>(std::min(spec.chunk, size - done)));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) fail("cannot read", in);
        done += n;
      }
      ::close(fd);
      phases.push_back({p, k, "read", t, now()});
      t = now();
      compute(spec.compute);
      phases.push_back({p, k, "compute", t, now()});
      t = now();
      const int wfd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
      if (wfd < 0) fail("cannot make", out);
      try {
        write_all(wfd, buffer, size, spec.chunk, out);
      } catch (...) {
        ::close(wfd);
        throw;
      }
      ::close(wfd);
      phases.push_back({p, k, "write", t, now()});
    } catch (...) {
      release();
      throw;
    }
    release();
  }
  return phases;
}

}  // namespace

RealRun run_real(const RealCase& spec, const std::filesystem::path& dir, int repetition, double sample_interval, double settle_limit) {
  RealRun run;
  run.spec = spec;
  run.repetition = repetition;
  const Scratch scratch(dir, "pcsim-here");
  for (int p = 1; p <= spec.pipelines; ++p) {
    check_stopped();
    make_input(scratch.file(fmt::format("p{}_file_1", p)), spec.file_size);
  }
  run.dropped_all_caches = ::geteuid() == 0 && drop_all_caches();
  if (!run.dropped_all_caches) {
    ::sync();
    for (int p = 1; p <= spec.pipelines; ++p) drop_file(scratch.file(fmt::format("p{}_file_1", p)));
  }
  if (reported_free_bytes() >= 0) run.warm_at_start = wait_for_reporting(settle_limit) ? 0 : -1;
  const std::string meminfo = read_meminfo();
  run.memory_total = meminfo_bytes(meminfo, "MemTotal");
  run.in_use_at_start = run.memory_total - meminfo_bytes(meminfo, "MemAvailable");
  run.free_at_start = meminfo_bytes(meminfo, "MemFree");

  std::atomic<bool> done{false};
  std::mutex lock;
  std::vector<std::exception_ptr> errors;
  const ActivityMark activity;
  const auto start = Clock::now();
  {
    std::jthread sampler([&] {
      while (!done.load()) {
        run.memory.push_back(sample(std::chrono::duration<double>(Clock::now() - start).count()));
        std::this_thread::sleep_for(std::chrono::duration<double>(sample_interval));
      }
      run.memory.push_back(sample(std::chrono::duration<double>(Clock::now() - start).count()));
    });
    {
      std::vector<std::jthread> pipelines;
      for (int p = 1; p <= spec.pipelines; ++p) {
        pipelines.emplace_back([&, p] {
          try {
            std::vector<RealPhase> phases = pipeline(spec, scratch, p, start);
            const std::lock_guard<std::mutex> guard(lock);
            run.phases.insert(run.phases.end(), phases.begin(), phases.end());
          } catch (...) {
            const std::lock_guard<std::mutex> guard(lock);
            errors.push_back(std::current_exception());
          }
        });
      }
    }
    done.store(true);
  }
  if (!errors.empty()) std::rethrow_exception(errors.front());
  const Activity seen = activity.since();
  run.others_busy_cores = seen.others_busy_cores;
  run.steal_pct = seen.steal_pct;
  run.reported = seen.reported;
  std::sort(run.phases.begin(), run.phases.end(), [](const RealPhase& a, const RealPhase& b) {
    return std::tie(a.pipeline, a.task, a.start) < std::tie(b.pipeline, b.task, b.start);
  });
  for (const RealPhase& ph : run.phases) run.makespan = std::max(run.makespan, ph.end);
  return run;
}

}  // namespace pagecache::calibrate
