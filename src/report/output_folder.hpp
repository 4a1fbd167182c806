#pragma once
// A run's output folder, made whole before it appears. The outputs are written into a fresh
// hidden staging folder next to the target; commit() then puts it in the target's place in one
// rename, so that a reader or a concurrent run sees the old folder or the new one, never a
// mix. A folder replaced is deleted name by name, and only if it is pcsim's (output_rules.hpp).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pagecache::report {

class RemovedOnInterrupt;

class OutputFolder {
 public:
  /// How commit() replaces an existing folder: one renameat2(RENAME_EXCHANGE), or a rename
  /// aside and a rename in (what commit() falls back to where the filesystem cannot exchange).
  enum class Swap { Exchange, AsideThenIn };

  /// Makes the staging folder, with the marker in it, next to the folder `dir` names (and the
  /// folders above, as needed; removed again if the run fails while they are empty). First
  /// removes the staging folders that runs killed beyond catching left beside it (theirs by
  /// name, marker and content; their process gone). Throws ConfigError for an empty `dir`,
  /// Error if it cannot.
  explicit OutputFolder(const std::string& dir);
  /// Not committed (the run failed): removes the staging folder, and only it, and the folders
  /// above it that it made, if empty.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& staging() const { return staging_; }

  /// Puts the staging folder in the target's place. Checks the target again first and throws
  /// ConfigError (see refuse()) if it may not be replaced now; throws Error if a rename fails.
  /// Returns warnings for the user: a replaced folder kept because someone wrote into it.
  std::vector<std::string> commit(Swap swap = Swap::Exchange);

 private:
  std::string dir_;  // as the user wrote it, for messages
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
  std::vector<std::filesystem::path> made_;        // folders above made for it, deepest first
  std::unique_ptr<RemovedOnInterrupt> cleanup_;    // the staging folder, if interrupted
  void remove_made_folders();
};

/// Deletes `old`, the folder that was just put aside from `target`, if it is pcsim's: its
/// output files, then the folder. Otherwise moves it, whole, into a visible new folder
/// "<target>.kept-<pid>-<hex>" and returns a warning naming it.
std::optional<std::string> remove_replaced(const std::filesystem::path& old, const std::filesystem::path& target);

}  // namespace pagecache::report
