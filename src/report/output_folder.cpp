#include "report/output_folder.hpp"

#include "report/output_rules.hpp"
#include "report/unique_name.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace pagecache::report {

namespace fs = std::filesystem;

namespace {

// Two runs replacing one folder take a few rounds at most; more means it is being fought over.
constexpr int kAttempts = 50;

// What a rename fails with when another process removed, made or changed the target meanwhile.
bool changed_meanwhile(int error) {
  return error == ENOENT || error == EEXIST || error == ENOTEMPTY || error == ENOTDIR || error == EISDIR;
}

[[noreturn]] void fail(const std::string& what, int error) {
  throw Error(fmt::format("{}: {}", what, std::generic_category().message(error)));
}

// pcsim's own files in `folder`, then the folder: never anything else. True if it is gone.
bool remove_own_files(const fs::path& folder) {
  for (const char* name : kOutputNames) ::unlink((folder / name).c_str());
  return ::rmdir(folder.c_str()) == 0 || errno == ENOENT;
}

}  // namespace

OutputFolder::OutputFolder(const std::string& dir) : dir_(dir), target_(output_folder_path(dir)) {
  std::error_code ec;
  fs::create_directories(target_.parent_path(), ec);
  if (ec) throw Error(fmt::format("cannot make the folder {}: {}", target_.parent_path().string(), ec.message()));
  staging_ = create_unique_folder(target_.parent_path(), fmt::format(".{}.tmp", target_.filename().string()));
  // First, so that a staging folder left by a killed run is recognisably pcsim's.
  std::ofstream marker(staging_ / kMarkerName, std::ios::binary);
  marker << kMarkerText;
  marker.close();
  if (!marker) {
    ::unlink((staging_ / kMarkerName).c_str());
    ::rmdir(staging_.c_str());
    throw Error(fmt::format("cannot write {}", (staging_ / kMarkerName).string()));
  }
}

OutputFolder::~OutputFolder() {
  if (!committed_) remove_own_files(staging_);
}

std::vector<std::string> OutputFolder::commit(Swap swap) {
  std::vector<std::string> warnings;
  auto retire = [&](const fs::path& old) {
    if (auto warning = remove_replaced(old, target_)) warnings.push_back(*warning);
  };
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    struct stat st{};
    if (::lstat(target_.c_str(), &st) != 0 && errno == ENOENT) {
      // Fails (EEXIST or ENOTEMPTY) if another run made the folder meanwhile: then replace it.
      if (::rename(staging_.c_str(), target_.c_str()) == 0) {
        committed_ = true;
        return warnings;
      }
      if (!changed_meanwhile(errno)) fail(fmt::format("cannot rename {} to {}", staging_.string(), target_.string()), errno);
      continue;
    }
    if (const auto why = refusal(target_)) refuse(dir_, target_, *why);
    ::chmod(staging_.c_str(), st.st_mode & 07777);  // an empty folder made for pcsim keeps its permissions
    if (swap == Swap::Exchange) {
      if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
        committed_ = true;
        retire(staging_);  // which now holds the folder replaced
        return warnings;
      }
      if (changed_meanwhile(errno)) continue;
      if (errno != EINVAL && errno != ENOSYS) fail(fmt::format("cannot replace {}", target_.string()), errno);
      swap = Swap::AsideThenIn;
    }
    const fs::path aside = create_unique_folder(target_.parent_path(), fmt::format(".{}.old", target_.filename().string()));
    if (::rename(target_.c_str(), aside.c_str()) != 0) {
      const int error = errno;
      ::rmdir(aside.c_str());
      if (changed_meanwhile(error)) continue;
      fail(fmt::format("cannot move {} aside", target_.string()), error);
    }
    const bool in = ::rename(staging_.c_str(), target_.c_str()) == 0;
    const int error = errno;
    retire(aside);
    if (in) {
      committed_ = true;
      return warnings;
    }
    // Another run's folder came in between: go round and replace that one.
    if (!changed_meanwhile(error)) fail(fmt::format("cannot rename {} to {}", staging_.string(), target_.string()), error);
  }
  throw Error(fmt::format("gave up replacing {} after {} attempts: other processes keep replacing it", target_.string(), kAttempts));
}

std::optional<std::string> remove_replaced(const fs::path& old, const fs::path& target) {
  std::optional<std::string> why = refusal(old);
  if (!why) {
    if (remove_own_files(old)) return std::nullopt;
    why = "was not empty once pcsim's files were removed";
  }
  // Someone wrote into it while it was being replaced: not pcsim's to delete.
  fs::path now = old;
  try {
    const fs::path kept = create_unique_folder(target.parent_path(), fmt::format("{}.kept", target.filename().string()));
    if (::rename(old.c_str(), (kept / target.filename()).c_str()) == 0) now = kept / target.filename();
    else ::rmdir(kept.c_str());
  } catch (const Error&) {
    // No folder to keep it in: it stays where it is, which the warning names.
  }
  return fmt::format("{} changed while pcsim replaced it: the folder replaced {}, so it was not removed; it is now {}", target.string(),
                     *why, now.string());
}

}  // namespace pagecache::report
