#include "report/replace_file.hpp"

#include "report/unique_name.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace pagecache::report {

namespace fs = std::filesystem;

void check_output_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(fs::status(path, ec))) throw ConfigError(fmt::format("--json {}: is a folder; name a file", path));
}

void replace_file(const std::string& path, const std::string& text) {
  check_output_file(path);
  const fs::path target = fs::absolute(path);
  auto cannot_write = [&path](int error) { return Error(fmt::format("cannot write {}: {}", path, std::generic_category().message(error))); };
  const fs::path temp = create_unique(target.parent_path(), fmt::format(".{}.tmp", target.filename().string()), [&](const fs::path& p) {
    const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST) return false;
    if (fd < 0) throw cannot_write(errno);
    struct stat old{};
    if (::stat(target.c_str(), &old) == 0) ::fchmod(fd, old.st_mode & 07777);
    ::close(fd);
    return true;
  });
  std::ofstream out(temp, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    ::unlink(temp.c_str());
    throw Error(fmt::format("cannot write {}", path));
  }
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    const int error = errno;
    ::unlink(temp.c_str());
    if (error == EISDIR) check_output_file(path);  // it became a folder meanwhile
    throw cannot_write(error);
  }
}

}  // namespace pagecache::report
