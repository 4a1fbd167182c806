#pragma once
// Scratch: the files of one measurement, in a folder of their own inside the user's, removed
// whole when it goes (an interruption included): nothing else there is touched.

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

namespace pagecache::calibrate {

class Scratch {
 public:
  Scratch(const std::filesystem::path& dir, const std::string& prefix) {
    std::string pattern = (dir / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw ConfigError(fmt::format("--dir '{}': cannot make a folder there ({})", dir.string(), std::strerror(errno)));
    }
    path_ = pattern;
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::filesystem::path file(const std::string& name) const { return path_ / name; }
  void remove(const std::filesystem::path& file) const {
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
  }

 private:
  std::filesystem::path path_;
};

}  // namespace pagecache::calibrate
