#include "report/unique_name.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <random>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace pagecache::report {

namespace fs = std::filesystem;

fs::path create_unique(const fs::path& folder, const std::string& stem, const std::function<bool(const fs::path&)>& create) {
  std::random_device random;
  // 2^32 names per pid: a taken one is a coincidence, and a hundred in a row a broken folder.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path path = folder / fmt::format("{}-{}-{:08x}", stem, ::getpid(), random());
    if (create(path)) return path;
  }
  throw Error(fmt::format("cannot make a new name {}-* in {}: all taken", stem, folder.string()));
}

fs::path create_unique_folder(const fs::path& folder, const std::string& stem) {
  return create_unique(folder, stem, [](const fs::path& path) {
    if (::mkdir(path.c_str(), 0777) == 0) return true;
    if (errno == EEXIST) return false;
    throw Error(fmt::format("cannot make the folder {}: {}", path.string(), std::generic_category().message(errno)));
  });
}

}  // namespace pagecache::report
