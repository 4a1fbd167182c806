#include "report/output_rules.hpp"

#include "report/unique_name.hpp"
#include "text/path_problem.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <sys/stat.h>
#include <system_error>
#include <vector>

namespace pagecache::report {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kNameTooLong = "is a name longer than the file system allows";
constexpr std::string_view kCannotExamine = "cannot be examined";

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// Compared by device and inode, so that a path through a link or a bind mount is recognised.
bool is_current_or_above(const struct stat& folder) {
  std::error_code ec;
  fs::path p = fs::current_path(ec);
  for (; !ec && !p.empty(); p = p.parent_path()) {
    struct stat st{};
    if (::stat(p.c_str(), &st) == 0 && same_file(st, folder)) return true;
    if (p == p.root_path()) break;
  }
  return false;
}

bool is_mount_point(const fs::path& folder, const struct stat& st) {
  struct stat parent{};
  return ::stat((folder / "..").c_str(), &parent) == 0 && parent.st_dev != st.st_dev;
}

bool is_within(const fs::path& path, const fs::path& folder) {
  return std::mismatch(folder.begin(), folder.end(), path.begin(), path.end()).first == folder.end();
}

bool is_output_name(const std::string& name) {
  return std::find(std::begin(kOutputNames), std::end(kOutputNames), name) != std::end(kOutputNames);
}

}  // namespace

fs::path output_folder_path(const std::string& dir) {
  if (dir.empty()) throw ConfigError("--out is empty: name the output folder (the default is pcsim-out)");
  if (const std::string nul = text::nul_problem(dir); !nul.empty()) throw ConfigError(text::path_message("--out", dir, nul));
  // A folder above that cannot be resolved (a symbolic link loop, a name too long, no
  // permission) is the option's problem, named as such.
  std::error_code ec;
  fs::path path = fs::absolute(dir, ec);
  if (ec) throw ConfigError(text::path_message("--out", dir, "cannot be resolved", ec));
  while (!path.has_filename() && path != path.root_path()) path = path.parent_path();  // "out/" names out
  const fs::path name = path.filename();
  const bool whole = name.empty() || name == "." || name == "..";
  fs::path resolved = fs::weakly_canonical(whole ? path : path.parent_path(), ec);
  if (ec) throw ConfigError(text::path_message("--out", dir, "cannot be resolved", ec));
  return whole ? resolved : resolved / name;
}

std::optional<std::string> refusal(const fs::path& path, const std::string& scenario_file) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return std::nullopt;
    if (errno == ENAMETOOLONG) return std::string(kNameTooLong);
    return fmt::format("{} ({})", kCannotExamine, std::generic_category().message(errno));
  }
  if (S_ISLNK(st.st_mode)) return "is a symbolic link (pcsim neither replaces a link nor writes through one)";
  if (!S_ISDIR(st.st_mode)) return "is not a folder";
  if (is_current_or_above(st)) return "is the current folder or one above it";
  // A mount point cannot be renamed, which replacing a folder needs.
  if (is_mount_point(path, st)) return "is a mount point (name a folder inside it)";
  std::error_code ec;
  if (!scenario_file.empty() && is_within(fs::weakly_canonical(scenario_file, ec), path)) {
    return fmt::format("holds the scenario file {}", scenario_file);
  }
  std::vector<std::string> names;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) names.push_back(it->path().filename().string());
  if (ec) return fmt::format("cannot be listed ({})", ec.message());
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    struct stat entry{};
    const bool regular = ::lstat((path / name).c_str(), &entry) == 0 && S_ISREG(entry.st_mode);
    if (!regular || !is_output_name(name)) return fmt::format("holds '{}', which pcsim did not write", name);
  }
  if (!names.empty() && !std::binary_search(names.begin(), names.end(), kMarkerName)) {
    return fmt::format("holds no {} marker, so pcsim did not make it (older versions did not mark their folders)", kMarkerName);
  }
  return std::nullopt;
}

void refuse(const std::string& dir, const fs::path& path, const std::string& reason) {
  // A name the file system refuses, or cannot examine, is not about what the folder holds.
  if (reason == kNameTooLong || reason.rfind(kCannotExamine, 0) == 0) throw ConfigError(fmt::format("--out {}: {} {}", dir, path.string(), reason));
  throw ConfigError(fmt::format("--out {}: will not replace {}: it {}. pcsim replaces only an empty folder or one it made (marked by "
                                "{}) that holds nothing else; nothing was removed",
                                dir, path.string(), reason, kMarkerName));
}

std::optional<std::string> cannot_replace(const fs::path& path) {
  const auto flagged = [](const fs::path& p, int open_flags) -> bool {
    const int fd = ::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | open_flags);
    if (fd < 0) return false;
    int flags = 0;
    const bool got = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;  // ENOTTY where a file system has no such flags
    ::close(fd);
    return got && (flags & (FS_IMMUTABLE_FL | FS_APPEND_FL)) != 0;
  };
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return std::nullopt;
  if (flagged(path, O_DIRECTORY)) return std::string("it is immutable or append-only (chattr +i or +a; lsattr -d shows it)");
  for (const char* name : kOutputNames) {
    if (flagged(path / name, 0)) return fmt::format("its {} is immutable or append-only (chattr +i or +a; lsattr shows it)", name);
  }
  return std::nullopt;
}

void check_output_folder(const std::string& dir, const std::string& scenario_file) {
  const fs::path path = output_folder_path(dir);
  if (const auto why = refusal(path, scenario_file)) refuse(dir, path, *why);
  if (const auto why = cannot_replace(path)) {
    throw ConfigError(fmt::format("--out {}: pcsim cannot replace {}: {}; nothing was removed", dir, path.string(), *why));
  }
  // The staging folder goes beside the target, in folders made as needed: the nearest folder
  // that exists must take a new one.
  fs::path existing = path.parent_path();
  struct stat st{};
  while (::lstat(existing.c_str(), &st) != 0 && existing != existing.parent_path()) existing = existing.parent_path();
  if (const int error = probe_folder(existing, true); error != 0) {
    throw ConfigError(fmt::format("--out {}: pcsim cannot make a folder in {} ({})", dir, existing.string(), std::generic_category().message(error)));
  }
}

}  // namespace pagecache::report
