#include "report/output_folder.hpp"

#include "report/interrupt_cleanup.hpp"
#include "report/output_rules.hpp"
#include "report/unique_name.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <string_view>
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

// The folder --out names could not be made or put in place: the option's problem (exit 2).
[[noreturn]] void fail(const std::string& dir, const std::string& what, int error) {
  throw ConfigError(fmt::format("--out {}: {}: {}", dir, what, std::generic_category().message(error)));
}

// Staging folders are "<stem>-<pid>-<8 hex digits>"; staging_pid also takes the older form
// ".<target>.tmp-<pid>-<hex>". Temporary files inside one are OutputFile's ".pcsim.tmp-...".
// Matched by hand: compiling a std::regex is a large part of a small run's fixed cost.
constexpr const char* kStagingStem = ".pcsim.tmp";

bool all_chars(std::string_view s, bool (*is)(char)) { return std::all_of(s.begin(), s.end(), is); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_hex(char c) { return is_digit(c) || (c >= 'a' && c <= 'f'); }

// `name` ends in "<digits>-<8 hex digits>": where the digits start, or npos.
std::size_t pid_and_tag_at(std::string_view name) {
  if (name.size() < 10 || !all_chars(name.substr(name.size() - 8), is_hex) || name[name.size() - 9] != '-') return std::string_view::npos;
  std::size_t start = name.size() - 9;
  while (start > 0 && is_digit(name[start - 1])) --start;
  return start == name.size() - 9 ? std::string_view::npos : start;
}

// A staging folder's name, ".<anything>.tmp-<pid>-<8 hex digits>": its pid's digits, or empty.
std::string_view staging_pid(std::string_view name) {
  const std::size_t start = pid_and_tag_at(name);
  if (start == std::string_view::npos || start < 6 || name[0] != '.' || name.substr(start - 5, 5) != ".tmp-") return {};
  return name.substr(start, name.size() - 9 - start);
}

// OutputFile's temporary files: ".pcsim.tmp-<pid>-<8 hex digits>".
bool is_temporary_file_name(std::string_view name) {
  constexpr std::string_view kPrefix = ".pcsim.tmp-";
  return name.substr(0, kPrefix.size()) == kPrefix && pid_and_tag_at(name) == kPrefix.size();
}

// pcsim's own files in `folder`, then the folder: never anything else. True if it is gone.
bool remove_own_files(const fs::path& folder) {
  for (const char* name : kOutputNames) ::unlink((folder / name).c_str());
  return ::rmdir(folder.c_str()) == 0 || errno == ENOENT;
}

bool process_gone(long pid) { return pid > 0 && pid <= INT_MAX && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

// A staging folder its process left (killed beyond catching): named as pcsim names them, its
// process gone, holding pcsim's marker as pcsim writes it and nothing but pcsim's outputs and
// temporary files. Anything else in `parent` is left alone.
void remove_abandoned_staging(const fs::path& parent) {
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string_view digits = staging_pid(name);
    if (digits.empty()) continue;
    long pid = 0;
    try {
      pid = std::stol(std::string(digits));
    } catch (const std::exception&) {
      continue;
    }
    struct stat st{};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || !process_gone(pid)) continue;
    std::ifstream marker(it->path() / kMarkerName, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(marker)), std::istreambuf_iterator<char>());
    if (text != kMarkerText) continue;
    std::vector<fs::path> temporaries;
    bool only_pcsim = true;
    std::error_code inner;
    for (fs::directory_iterator f(it->path(), inner), fend; !inner && f != fend; f.increment(inner)) {
      const std::string file = f->path().filename().string();
      struct stat fst{};
      const bool regular = ::lstat(f->path().c_str(), &fst) == 0 && S_ISREG(fst.st_mode);
      if (regular && is_temporary_file_name(file)) temporaries.push_back(f->path());
      else if (!regular || std::find(std::begin(kOutputNames), std::end(kOutputNames), file) == std::end(kOutputNames)) only_pcsim = false;
    }
    if (inner || !only_pcsim) continue;
    for (const fs::path& t : temporaries) ::unlink(t.c_str());
    remove_own_files(it->path());
  }
}

}  // namespace

OutputFolder::OutputFolder(const std::string& dir) : dir_(dir), target_(output_folder_path(dir)) {
  const fs::path parent = target_.parent_path();
  // The folders above, made as needed; removed again (if still empty) should the run fail.
  std::vector<fs::path> missing;
  struct stat st{};
  for (fs::path p = parent; ::lstat(p.c_str(), &st) != 0 && errno == ENOENT && p != p.parent_path(); p = p.parent_path()) {
    missing.push_back(p);
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) == 0) {
      made_.insert(made_.begin(), *it);  // deepest first
    } else if (errno != EEXIST) {
      const int error = errno;
      remove_made_folders();
      fail(dir_, fmt::format("cannot make the folder {}", it->string()), error);
    }
  }
  if (::stat(parent.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    remove_made_folders();
    throw ConfigError(fmt::format("--out {}: cannot make the folder {}: it is not a folder", dir_, parent.string()));
  }
  remove_abandoned_staging(parent);
  // Made and registered with signals held, so that no interruption falls between the two.
  const SignalsHeld held;
  try {
    // A short name, so that a target name at the file system's limit still has a staging one.
    staging_ = create_unique_folder(parent, kStagingStem);
  } catch (...) {
    remove_made_folders();
    throw;
  }
  cleanup_ = std::make_unique<RemovedOnInterrupt>(staging_.string(), RemovedOnInterrupt::Kind::StagingFolder);
  // First, so that a staging folder left by a killed run is recognisably pcsim's.
  std::ofstream marker(staging_ / kMarkerName, std::ios::binary);
  marker << kMarkerText;
  marker.close();
  if (!marker) {
    ::unlink((staging_ / kMarkerName).c_str());
    ::rmdir(staging_.c_str());
    remove_made_folders();
    throw ConfigError(fmt::format("--out {}: cannot write {}", dir_, (staging_ / kMarkerName).string()));
  }
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  remove_own_files(staging_);
  remove_made_folders();
}

void OutputFolder::remove_made_folders() {
  for (const fs::path& p : made_) ::rmdir(p.c_str());  // deepest first; a folder in use stays
  made_.clear();
}

std::vector<std::string> OutputFolder::commit(Swap swap) {
  std::vector<std::string> warnings;
  auto retire = [&](const fs::path& old) {
    if (auto warning = remove_replaced(old, target_)) warnings.push_back(*warning);
  };
  // Signals held until the folder is in place and no longer registered for removal: an
  // interruption in between would remove the folder just put in place, or leave the staging one.
  const SignalsHeld held;
  auto done = [&] {
    committed_ = true;
    cleanup_.reset();
  };
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    struct stat st{};
    if (::lstat(target_.c_str(), &st) != 0 && errno == ENOENT) {
      // Fails (EEXIST or ENOTEMPTY) if another run made the folder meanwhile: then replace it.
      if (::rename(staging_.c_str(), target_.c_str()) == 0) {
        done();
        return warnings;
      }
      if (!changed_meanwhile(errno)) fail(dir_, fmt::format("cannot rename {} to {}", staging_.string(), target_.string()), errno);
      continue;
    }
    if (const auto why = refusal(target_)) refuse(dir_, target_, *why);
    ::chmod(staging_.c_str(), st.st_mode & 07777);  // an empty folder made for pcsim keeps its permissions
    if (swap == Swap::Exchange) {
      if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
        done();
        retire(staging_);  // which now holds the folder replaced
        return warnings;
      }
      if (changed_meanwhile(errno)) continue;
      if (errno != EINVAL && errno != ENOSYS) fail(dir_, fmt::format("cannot replace {}", target_.string()), errno);
      swap = Swap::AsideThenIn;
    }
    const fs::path aside = create_unique_folder(target_.parent_path(), ".pcsim.old");
    if (::rename(target_.c_str(), aside.c_str()) != 0) {
      const int error = errno;
      ::rmdir(aside.c_str());
      if (changed_meanwhile(error)) continue;
      fail(dir_, fmt::format("cannot move {} aside", target_.string()), error);
    }
    const bool in = ::rename(staging_.c_str(), target_.c_str()) == 0;
    const int error = errno;
    if (in) done();
    retire(aside);
    if (in) return warnings;
    // Another run's folder came in between: go round and replace that one.
    if (!changed_meanwhile(error)) fail(dir_, fmt::format("cannot rename {} to {}", staging_.string(), target_.string()), error);
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
