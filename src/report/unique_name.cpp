#include "report/unique_name.hpp"

#include "report/interrupt_cleanup.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <fcntl.h>
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

int probe_folder(const fs::path& folder, bool as_folder) {
  const SignalsHeld held;
  int error = 0;
  const fs::path probe = create_unique(folder, ".pcsim.tmp", [&](const fs::path& path) {
    int fd = -1;
    const bool made = as_folder ? ::mkdir(path.c_str(), 0700) == 0 : (fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600)) >= 0;
    if (!made && errno == EEXIST) return false;
    if (!made) error = errno;
    if (fd >= 0) ::close(fd);
    return true;
  });
  if (error == 0) (void)(as_folder ? ::rmdir(probe.c_str()) : ::unlink(probe.c_str()));
  return error;
}

}  // namespace pagecache::report
