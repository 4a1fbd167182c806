#include "formats/common/text_file.hpp"

#include "text/path_problem.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pagecache::formats {

namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void fail(std::string_view argument, const std::string& path, const std::string& why) {
  throw ConfigError(text::path_message(argument, path, why));
}

// The file opened, if it may be read as a `what`: a regular file of at most kMaxTextFileBytes.
void open_checked(Descriptor& file, struct stat& info, std::string_view argument, const std::string& path, const char* what) {
  if (const std::string nul = text::nul_problem(path); !nul.empty()) fail(argument, path, nul);
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one; the
  // type is then checked on the open file itself, so that it cannot change in between.
  file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (file.fd < 0) fail(argument, path, fmt::format("cannot open the {}: {}", what, std::strerror(errno)));
  if (::fstat(file.fd, &info) != 0) fail(argument, path, fmt::format("cannot read the {}: {}", what, std::strerror(errno)));
  if (S_ISDIR(info.st_mode)) fail(argument, path, fmt::format("is a folder, not a {}", what));
  if (!S_ISREG(info.st_mode)) fail(argument, path, fmt::format("not a regular file (a device, FIFO or socket cannot be a {})", what));
  if (info.st_size > kMaxTextFileBytes) {
    fail(argument, path, fmt::format("{} bytes is too large for a {} (at most {} MiB)", info.st_size, what, kMaxTextFileBytes >> 20));
  }
}

}  // namespace

void check_text_file(std::string_view argument, const std::string& path, const char* what) {
  Descriptor file;
  struct stat info {};
  open_checked(file, info, argument, path, what);
}

std::string read_text_file(const std::string& path, const char* what) {
  Descriptor file;
  struct stat info {};
  open_checked(file, info, {}, path, what);
  // Read to its end, which a file growing meanwhile may move: the limit holds for what is read.
  std::string text;
  text.reserve(static_cast<std::size_t>(info.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ::ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail({}, path, fmt::format("cannot read the {}: {}", what, std::strerror(errno)));
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > static_cast<std::size_t>(kMaxTextFileBytes)) {
      fail({}, path, fmt::format("too large for a {} (at most {} MiB)", what, kMaxTextFileBytes >> 20));
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace pagecache::formats
