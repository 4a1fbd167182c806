#pragma once
// What a sweep's runs are made of besides their overrides: the base's files, by their bytes,
// and the settings that change results (the profile; a workflow's files_host and hosts). Its
// fingerprint goes into sweep-plan.json and every results line, so that a folder holds the
// results of one sweep only: results of another base, or of this base edited since, are
// refused instead of merged.

#include <string>
#include <vector>

namespace pagecache::sweep {

struct BaseFile {
  std::string role;  ///< "scenario", "platform" or "workflow"
  std::string path;  ///< absolute, or "<embedded default>"
  std::string hash;  ///< FNV-1a of its bytes, 16 hex digits
  friend bool operator==(const BaseFile&, const BaseFile&) = default;
};

struct BaseIdentity {
  std::vector<BaseFile> files;
  std::string settings;  ///< e.g. "profile = paper", or empty

  /// 16 hex digits of the roles, hashes and settings: the files' paths are left out, so that
  /// a sweep's inputs moved elsewhere (another mount of the same share) are the same base.
  std::string fingerprint() const;
};

/// The base a sweep names, read now. `scenario`: its absolute path, or empty;
/// `workflow_text`: the TOML naming its workflow and platform, or empty; neither: the embedded
/// default. The files read are those a run reads: the scenario file, its platform file (of
/// the profile in use) and its workflow file, or the workflow's and its platform's. Throws
/// ConfigError if one cannot be read.
BaseIdentity identify_base(const std::string& scenario, const std::string& workflow_text, const std::string& profile);

/// What differs from `before` (the base of a folder's results) to `now`, for a person: e.g.
/// "/x/exp2.toml (the scenario file) has changed since". Empty if the fingerprints agree.
std::string base_changes(const BaseIdentity& before, const BaseIdentity& now);

}  // namespace pagecache::sweep
