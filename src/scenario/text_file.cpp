#include "scenario/text_file.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::scenario {

namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_text_file(const std::string& path, const char* what) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one; the
  // type is then checked on the open file itself, so that it cannot change in between.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) throw ConfigError(fmt::format("{}: cannot open the {}: {}", path, what, std::strerror(errno)));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) throw ConfigError(fmt::format("{}: cannot read the {}: {}", path, what, std::strerror(errno)));
  if (S_ISDIR(info.st_mode)) throw ConfigError(fmt::format("{}: is a folder, not a {}", path, what));
  if (!S_ISREG(info.st_mode)) throw ConfigError(fmt::format("{}: not a regular file (a device, FIFO or socket cannot be a {})", path, what));
  if (info.st_size > kMaxTextFileBytes) {
    throw ConfigError(fmt::format("{}: {} bytes is too large for a {} (at most {} MiB)", path, info.st_size, what, kMaxTextFileBytes >> 20));
  }
  // Read to its end, which a file growing meanwhile may move: the limit holds for what is read.
  std::string text;
  text.reserve(static_cast<std::size_t>(info.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ::ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw ConfigError(fmt::format("{}: cannot read the {}: {}", path, what, std::strerror(errno)));
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > static_cast<std::size_t>(kMaxTextFileBytes)) {
      throw ConfigError(fmt::format("{}: too large for a {} (at most {} MiB)", path, what, kMaxTextFileBytes >> 20));
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace pagecache::scenario
