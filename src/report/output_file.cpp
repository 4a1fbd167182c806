#include "report/output_file.hpp"

#include "report/interrupt_cleanup.hpp"
#include "report/unique_name.hpp"
#include "text/path_problem.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <optional>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>
#include <utility>
#include <vector>

namespace pagecache::report {

namespace fs = std::filesystem;

namespace {

// Where the bytes for `path` go: one of pcsim's own descriptors, a device or FIFO written
// through, or a regular file (absent, or a link's target) replaced whole.
struct Destination {
  enum class Way { OwnDescriptor, Through, Replace } way = Way::Replace;
  int fd = -1;          // OwnDescriptor
  std::string target;   // Replace: the regular file to put in place
};

// The folder a file is in ("." for a bare name).
fs::path folder_of(const std::string& path) {
  const fs::path folder = fs::path(path).parent_path();
  return folder.empty() ? fs::path(".") : folder;
}

std::string named(const std::string& path, std::string_view option) {
  return option.empty() ? path : fmt::format("{} {}", option, path);
}

[[noreturn]] void refuse(const std::string& path, std::string_view option, const std::string& why) {
  throw ConfigError(fmt::format("{}: {}", named(path, option), why));
}

// /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: the descriptor N of this process.
std::optional<int> own_descriptor(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0) {
      int fd = -1;
      const char* first = path.data() + prefix.size();
      const char* last = path.data() + path.size();
      const auto [end, error] = std::from_chars(first, last, fd);
      if (error == std::errc() && end == last) return fd;
    }
  }
  return std::nullopt;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "is a folder; name a file";
  if (S_ISSOCK(mode)) return "is a socket; pcsim writes regular files, character devices and FIFOs";
  if (S_ISBLK(mode)) return "is a block device; pcsim writes regular files, character devices and FIFOs";
  return "is not a regular file, a character device or a FIFO";
}

// A file replaced whole is written beside it first: its folder must take a new file. `probe`:
// tried with one made and removed at once (root passes access() on /proc or a read-only mount);
// an OutputFile needs no probe, its temporary file is one.
Destination writable_folder(Destination d, const std::string& path, std::string_view option, bool probe) {
  const fs::path folder = folder_of(d.target);
  const int error = ::access(folder.c_str(), W_OK | X_OK) != 0 ? errno : probe ? probe_folder(folder, false) : 0;
  if (error != 0) {
    refuse(path, option, fmt::format("pcsim cannot write in the folder {} ({})", folder.string(), std::generic_category().message(error)));
  }
  return d;
}

Destination destination(const std::string& path, std::string_view option, bool probe) {
  if (path.empty()) refuse(path, option, "no file named");
  if (const auto fd = own_descriptor(path)) {
    if (::fcntl(*fd, F_GETFL) == -1) refuse(path, option, fmt::format("descriptor {} is not open", *fd));
    return {Destination::Way::OwnDescriptor, *fd, {}};
  }
  struct stat link{};
  if (::lstat(path.c_str(), &link) != 0) {
    if (errno != ENOENT) refuse(path, option, std::generic_category().message(errno));
    // A new file: its folder must exist (pcsim makes no folders for a file).
    const fs::path folder = folder_of(path);
    struct stat dir{};
    if (::stat(folder.c_str(), &dir) != 0 || !S_ISDIR(dir.st_mode)) {
      refuse(path, option, fmt::format("the folder {} does not exist", folder.string()));
    }
    return writable_folder({Destination::Way::Replace, -1, path}, path, option, probe);
  }
  struct stat st = link;
  if (S_ISLNK(link.st_mode) && ::stat(path.c_str(), &st) != 0) {
    if (errno == ELOOP) refuse(path, option, "is a link that leads back to itself");
    refuse(path, option, "is a link to nothing: pcsim does not make the file a link points to");
  }
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
    if (::access(path.c_str(), W_OK) != 0) refuse(path, option, std::generic_category().message(errno));
    return {Destination::Way::Through, -1, {}};
  }
  if (!S_ISREG(st.st_mode)) refuse(path, option, kind_of(st.st_mode));
  if (!S_ISLNK(link.st_mode)) return writable_folder({Destination::Way::Replace, -1, path}, path, option, probe);
  // A link to a regular file: that file is replaced, the link stays.
  std::unique_ptr<char, decltype(&std::free)> real(::realpath(path.c_str(), nullptr), &std::free);
  if (!real) refuse(path, option, std::generic_category().message(errno));
  return writable_folder({Destination::Way::Replace, -1, real.get()}, path, option, probe);
}

// The file could not take the output (a full disk, /dev/full, a quota): the option's problem,
// named as such (exit 2), not the simulation's.
[[noreturn]] void cannot_write(const std::string& path, std::string_view option, int error) {
  throw ConfigError(text::path_message(option, path, "cannot write", std::error_code(error, std::generic_category())));
}

}  // namespace

void check_output_file(const std::string& path, std::string_view option) { (void)destination(path, option, true); }

void check_not_an_input(const std::string& path, std::string_view option, const std::vector<std::string>& inputs) {
  struct stat out{};
  if (::stat(path.c_str(), &out) != 0 || !S_ISREG(out.st_mode)) return;  // replaces no file
  for (const std::string& input : inputs) {
    struct stat in{};
    if (::stat(input.c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino) {
      refuse(path, option, fmt::format("is {}, which pcsim reads for this command; name another file", input));
    }
  }
}

OutputFile::OutputFile(const std::string& path, std::string_view option) : path_(path), option_(option) {
  const Destination d = destination(path, option, false);
  switch (d.way) {
    case Destination::Way::OwnDescriptor:
      fd_ = d.fd;
      own_fd_ = false;
      return;
    case Destination::Way::Through:
      fd_ = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (fd_ < 0) cannot_write(path, option, errno);
      return;
    case Destination::Way::Replace:
      break;
  }
  target_ = d.target;
  const fs::path folder = folder_of(target_);
  // A short name, so that a target name at the file system's limit still has a temporary one;
  // made and registered with signals held, so that no interruption falls between the two.
  const SignalsHeld held;
  temp_ = create_unique(folder, ".pcsim.tmp", [this](const fs::path& p) {
            fd_ = ::open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd_ < 0 && errno == EEXIST) return false;
            if (fd_ < 0) cannot_write(path_, option_, errno);
            return true;
          }).string();
  cleanup_ = std::make_unique<RemovedOnInterrupt>(temp_, RemovedOnInterrupt::Kind::File);
  struct stat old{};
  if (::stat(target_.c_str(), &old) == 0) ::fchmod(fd_, old.st_mode & 07777);
}

OutputFile::~OutputFile() {
  if (own_fd_ && fd_ >= 0) ::close(fd_);
  if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) cannot_write(path_, option_, n < 0 ? errno : EIO);
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void OutputFile::commit() {
  if (committed_) return;
  if (own_fd_) {
    const int fd = std::exchange(fd_, -1);
    if (::close(fd) != 0) cannot_write(path_, option_, errno);
  }
  if (!temp_.empty()) {
    // Checked again: the target may have become a folder (or a link) while pcsim worked.
    struct stat st{};
    if (::lstat(target_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
      refuse(path_, option_, S_ISLNK(st.st_mode) ? "became a link while pcsim wrote it; left as it is" : kind_of(st.st_mode));
    }
    if (::rename(temp_.c_str(), target_.c_str()) != 0) cannot_write(path_, option_, errno);
    cleanup_.reset();
  }
  committed_ = true;
}

void write_output_file(const std::string& path, std::string_view text, std::string_view option) {
  OutputFile file(path, option);
  file.write(text);
  file.commit();
}

}  // namespace pagecache::report
