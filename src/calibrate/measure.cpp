#include "calibrate/measure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <latch>
#include <memory>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace pagecache::calibrate {

namespace {

std::atomic<bool> g_stop{false};

extern "C" void on_stop_signal(int) { g_stop.store(true); }

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& file) {
  throw std::system_error(errno, std::generic_category(), fmt::format("{} '{}'", what, file.string()));
}

int open_file(const std::filesystem::path& file, int flags) {
  const int fd = ::open(file.c_str(), flags | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
  if (errno == EINVAL && (flags & O_DIRECT) != 0) throw DirectIoUnsupported(fmt::format("'{}': the file system refuses O_DIRECT", file.string()));
  fail("cannot open", file);
}

// A file descriptor closed when it goes.
class Fd {
 public:
  Fd(const std::filesystem::path& file, int flags) : fd_(open_file(file, flags)) {}
  ~Fd() { ::close(fd_); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const noexcept { return fd_; }

 private:
  int fd_;
};

// Memory aligned for O_DIRECT, filled (so touched) with a pattern that is not zeros.
struct AlignedBuffer {
  explicit AlignedBuffer(std::int64_t bytes) : size(bytes) {
    void* p = nullptr;
    if (::posix_memalign(&p, 4096, static_cast<std::size_t>(bytes)) != 0) throw std::bad_alloc();
    data.reset(static_cast<char*>(p));
    std::memset(data.get(), 0x5a, static_cast<std::size_t>(bytes));
  }
  struct Free {
    void operator()(char* p) const noexcept { std::free(p); }
  };
  std::unique_ptr<char, Free> data;
  std::int64_t size;
};

// Whether a loop measuring until `deadline` goes on: at least one request whatever the time
// (a deadline passed before the first, on a loaded machine, would measure nothing and leave a
// required key out of the platform), unless the user stopped calibrate.
bool go_on(std::int64_t done, const Deadline& deadline) { return done == 0 ? !g_stop.load(std::memory_order_relaxed) : !deadline.passed(); }

// Writes `size` bytes (or until the deadline) from `buffer` in requests of buffer.size.
std::int64_t write_loop(int fd, const AlignedBuffer& buffer, std::int64_t size, const Deadline& deadline, const std::filesystem::path& file,
                        bool direct) {
  std::int64_t done = 0;
  while (done < size && go_on(done, deadline)) {
    const auto n = ::pwrite(fd, buffer.data.get(), static_cast<std::size_t>(std::min(buffer.size, size - done)), done);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EINVAL && direct) throw DirectIoUnsupported(fmt::format("'{}': the file system refuses O_DIRECT writes", file.string()));
      fail("cannot write", file);
    }
    done += n;
  }
  return done;
}

std::int64_t read_loop(int fd, char* into, std::int64_t request, std::int64_t limit, bool advance, const Deadline& deadline,
                       const std::filesystem::path& file, bool direct) {
  std::int64_t done = 0;
  while (done < limit && go_on(done, deadline)) {
    const auto n = ::pread(fd, into + (advance ? done : 0), static_cast<std::size_t>(std::min(request, limit - done)), done);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EINVAL && direct) throw DirectIoUnsupported(fmt::format("'{}': the file system refuses O_DIRECT reads", file.string()));
      fail("cannot read", file);
    }
    if (n == 0) break;
    done += n;
  }
  return done;
}

std::int64_t size_of(const std::filesystem::path& file) { return static_cast<std::int64_t>(std::filesystem::file_size(file)); }

}  // namespace

bool Deadline::passed() const { return g_stop.load(std::memory_order_relaxed) || Clock::now() >= end_; }

void install_stop_handlers() {
  struct sigaction action{};
  action.sa_handler = on_stop_signal;
  ::sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

bool stop_requested() noexcept { return g_stop.load(); }

Rate direct_write(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline) {
  const AlignedBuffer buffer(request);
  const Fd fd(file, O_WRONLY | O_CREAT | O_TRUNC | O_DIRECT);
  const auto start = Clock::now();
  const std::int64_t done = write_loop(fd.get(), buffer, size, deadline, file, true);
  const double seconds = since(start);
  // Writeback does not flush the device's own cache, and neither is it timed here.
  if (::fdatasync(fd.get()) != 0) fail("cannot sync", file);
  return {done, seconds};
}

Rate direct_read(const std::filesystem::path& file, std::int64_t request, const Deadline& deadline) {
  const AlignedBuffer buffer(request);
  const Fd fd(file, O_RDONLY | O_DIRECT);
  const auto start = Clock::now();
  const std::int64_t done = read_loop(fd.get(), buffer.data.get(), request, size_of(file), false, deadline, file, true);
  return {done, since(start)};
}

Rate buffered_write_synced(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline) {
  const AlignedBuffer buffer(request);
  const Fd fd(file, O_WRONLY | O_CREAT | O_TRUNC);
  const auto start = Clock::now();
  const std::int64_t done = write_loop(fd.get(), buffer, size, deadline, file, false);
  if (::fsync(fd.get()) != 0) fail("cannot sync", file);
  return {done, since(start)};
}

Rate writeback(const std::vector<std::filesystem::path>& files, std::int64_t size, std::int64_t request) {
  const AlignedBuffer buffer(request);
  std::vector<std::unique_ptr<Fd>> open;
  for (const auto& file : files) {
    open.push_back(std::make_unique<Fd>(file, O_WRONLY | O_CREAT | O_TRUNC));
    write_loop(open.back()->get(), buffer, size, Deadline(600.0), file, false);
  }
  if (g_stop.load()) return {};
  const auto start = Clock::now();
  Rate total = in_threads(static_cast<int>(files.size()), [&](int i) {
    if (::fsync(open[static_cast<std::size_t>(i)]->get()) != 0) fail("cannot sync", files[static_cast<std::size_t>(i)]);
    return Rate{size, 0.0};
  });
  total.seconds = since(start);
  return total;
}

Rate buffered_read_cold(const std::filesystem::path& file, std::int64_t request, const Deadline& deadline) {
  const AlignedBuffer buffer(request);
  const Fd fd(file, O_RDONLY);
  ::fdatasync(fd.get());
  ::posix_fadvise(fd.get(), 0, 0, POSIX_FADV_DONTNEED);
  const auto start = Clock::now();
  const std::int64_t done = read_loop(fd.get(), buffer.data.get(), request, size_of(file), false, deadline, file, false);
  return {done, since(start)};
}

DirectAppender::DirectAppender(const std::filesystem::path& file, std::int64_t request)
    : file_(file), fd_(open_file(file, O_WRONLY | O_CREAT | O_TRUNC | O_DIRECT)), request_(request) {
  void* p = nullptr;
  if (::posix_memalign(&p, 4096, static_cast<std::size_t>(request)) != 0) {
    ::close(fd_);
    throw std::bad_alloc();
  }
  buffer_ = static_cast<char*>(p);
  // splitmix64: random bytes, fast enough not to be what is timed.
  std::uint64_t x = 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(::getpid());
  for (std::int64_t at = 0; at + 8 <= request; at += 8) {
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    std::memcpy(buffer_ + at, &z, 8);
  }
}

DirectAppender::~DirectAppender() {
  ::close(fd_);
  std::free(buffer_);
}

Rate DirectAppender::append(std::int64_t bytes, const Deadline& deadline) {
  std::int64_t done = 0;
  const auto start = Clock::now();
  while (done < bytes && !full_ && go_on(done, deadline)) {
    // Each 4 KiB block's first 8 bytes: a number no other block has (no deduplication).
    for (std::int64_t at = 0; at + 8 <= request_; at += 4096) {
      ++stamp_;
      std::memcpy(buffer_ + at, &stamp_, 8);
    }
    const auto n = ::pwrite(fd_, buffer_, static_cast<std::size_t>(request_), size_);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == ENOSPC || errno == EDQUOT) {
        full_ = true;
        break;
      }
      if (errno == EINVAL) throw DirectIoUnsupported(fmt::format("'{}': the file system refuses O_DIRECT writes", file_.string()));
      fail("cannot write", file_);
    }
    done += n;
    size_ += n;
    if (n < request_) full_ = true;  // a short write: the file system is (nearly) full
  }
  return {done, since(start)};
}

Rate concurrently(const std::vector<std::filesystem::path>& files, const std::function<Rate(const std::filesystem::path&)>& one) {
  return in_threads(static_cast<int>(files.size()), [&](int i) { return one(files[static_cast<std::size_t>(i)]); });
}

Rate in_threads(int threads, const std::function<Rate(int)>& one) {
  std::vector<Rate> rates(static_cast<std::size_t>(threads));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  std::latch ready(threads);
  {
    std::vector<std::jthread> pool;
    for (int i = 0; i < threads; ++i) {
      pool.emplace_back([&, i] {
        ready.arrive_and_wait();  // all start together
        try {
          rates[static_cast<std::size_t>(i)] = one(i);
        } catch (...) {
          errors[static_cast<std::size_t>(i)] = std::current_exception();
        }
      });
    }
  }
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  Rate total;
  for (const Rate& r : rates) {
    total.bytes += r.bytes;
    total.seconds = std::max(total.seconds, r.seconds);
  }
  return total;
}

Rate cache_write(const std::filesystem::path& file, std::int64_t size, std::int64_t request, const Deadline& deadline) {
  const AlignedBuffer buffer(request);
  const Fd fd(file, O_WRONLY | O_CREAT | O_TRUNC);
  const auto start = Clock::now();
  const std::int64_t done = write_loop(fd.get(), buffer, size, deadline, file, false);
  return {done, since(start)};
}

void sync_and_drop(const std::filesystem::path& file) {
  const Fd fd(file, O_RDONLY);
  ::fsync(fd.get());
  ::posix_fadvise(fd.get(), 0, 0, POSIX_FADV_DONTNEED);
}

void sync_file(const std::filesystem::path& file) {
  const Fd fd(file, O_RDONLY);
  if (::fsync(fd.get()) != 0) fail("cannot sync", file);
}

Rate cached_read(const std::filesystem::path& file, std::int64_t request, bool fresh, const Deadline& deadline) {
  const Fd fd(file, O_RDONLY);
  const std::int64_t size = size_of(file);
  // Pass after pass over the file until the deadline: a cached file is read in milliseconds.
  Rate total;
  const auto start = Clock::now();
  if (!fresh) {
    const AlignedBuffer buffer(request);
    do total.bytes += read_loop(fd.get(), buffer.data.get(), request, size, false, deadline, file, false);
    while (!deadline.passed());
    total.seconds = since(start);
    return total;
  }
  // Each pass into one new buffer of the file's size, as a task reading a file whole gets:
  // every page of it is first touched by the copy into it. Unmapping it is not timed.
  double unmapping = 0.0;
  do {
    void* memory = ::mmap(nullptr, static_cast<std::size_t>(size), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (memory == MAP_FAILED) throw std::bad_alloc();
    try {
      total.bytes += read_loop(fd.get(), static_cast<char*>(memory), request, size, true, deadline, file, false);
    } catch (...) {
      ::munmap(memory, static_cast<std::size_t>(size));
      throw;
    }
    const auto unmap = Clock::now();
    ::munmap(memory, static_cast<std::size_t>(size));
    unmapping += since(unmap);
  } while (!deadline.passed());
  total.seconds = since(start) - unmapping;
  return total;
}

Rate memory_copy(std::int64_t bytes, const Deadline& deadline, const std::function<void()>& before_destination) {
  const AlignedBuffer from(bytes);
  if (before_destination) before_destination();
  const AlignedBuffer to(bytes);
  volatile char sink = 0;
  std::int64_t done = 0;
  const auto start = Clock::now();
  while (!deadline.passed() || done == 0) {
    std::memcpy(to.data.get(), from.data.get(), static_cast<std::size_t>(bytes));
    sink = sink + to.data.get()[done % bytes];  // the copy is used
    done += bytes;
  }
  return {done, since(start)};
}

Rate first_touch(std::int64_t bytes, std::int64_t page_size, const Deadline& deadline) {
  void* memory = ::mmap(nullptr, static_cast<std::size_t>(bytes), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (memory == MAP_FAILED) throw std::bad_alloc();
  char* p = static_cast<char*>(memory);
  std::int64_t done = 0;
  const auto start = Clock::now();
  while (done < bytes) {
    const std::int64_t stop = std::min(bytes, done + 256 * page_size);  // the clock read every 256 pages
    for (; done < stop; done += page_size) p[done] = 1;
    if (deadline.passed()) break;
  }
  const double seconds = since(start);
  ::munmap(memory, static_cast<std::size_t>(bytes));
  return {std::min(done, bytes), seconds};
}

void MemoryHold::add(std::int64_t bytes) {
  if (bytes <= 0) return;
  void* data = ::mmap(nullptr, static_cast<std::size_t>(bytes), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (data == MAP_FAILED) throw std::bad_alloc();
  regions_.emplace_back(data, bytes);
  ::madvise(data, static_cast<std::size_t>(bytes), MADV_HUGEPAGE);  // fewer faults, where huge pages are allowed
  char* p = static_cast<char*>(data);
  for (std::int64_t at = 0; at < bytes && !stop_requested(); at += page_size_) p[at] = 1;
  held_ += bytes;
}

MemoryHold::~MemoryHold() {
  for (const auto& [data, bytes] : regions_) ::munmap(data, static_cast<std::size_t>(bytes));
}

}  // namespace pagecache::calibrate
