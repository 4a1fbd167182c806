#pragma once
// A sweep: one base scenario and the runs made of it, each a set of `--set` overrides. Read
// from a sweep file (TOML):
//
//   scenario = "scenarios/paper/exp2.toml"   # or workflow = "w.json" with platform = "p.xml",
//                                            # or neither: the embedded default
//   profile = "linux"                        # optional, as --profile
//   [[axes]]                                 # a grid over the axes (the first varies slowest)
//   key = "pipelines.count"
//   range = { from = 1, to = 32, step = 1 }  # or { from = 1, to = 1024, factor = 2 }
//   [[axes]]
//   key = "hosts.0.memory"
//   values = ["64 GB", "128 GB"]
//   # or, instead of axes, explicit runs: [[points]] tables of "key" = value
//
// Runs are made on demand from their index (a plan of 10^7 runs holds only its axes). A run's
// id is a hash of its overrides alone, sorted by key: adding a value to an axis, or reordering
// the axes, renames no run.

#include <pagecache/scenario_file.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pagecache::sweep {

/// One `--set` of a run: the key, its value as TOML text, and as a person reads it (a
/// string's text without quotes).
struct Override {
  std::string key;
  std::string toml;
  std::string shown;
  friend bool operator==(const Override&, const Override&) = default;
};

struct Run {
  std::size_t index = 0;  ///< in the plan's order
  std::string id;
  std::vector<Override> overrides;  ///< in the order of Plan::keys
};

/// Above this many runs a sweep needs --force (ten million: a day of small runs on 100 cores).
inline constexpr double kMaxRuns = 1e7;

class Plan {
 public:
  /// Reads the sweep file. Throws ConfigError naming the file, line and axis of the first
  /// problem: an unknown key, an empty axis, a range with step 0 or that never reaches its
  /// end, a value twice on one axis, two identical points, a value of the wrong type for its
  /// key (each axis value is tried on the base scenario), more than kMaxRuns runs without `force`.
  static Plan load(const std::string& path, bool force = false);
  /// The plan json() wrote (`origin` names it in errors). Throws ConfigError if it is not one.
  static Plan from_json(const std::string& text, const std::string& origin);

  const std::string& file() const noexcept { return file_; }
  /// The keys the runs override, in the sweep file's order: the axes of results.csv.
  const std::vector<std::string>& keys() const noexcept { return keys_; }
  std::size_t size() const noexcept { return size_; }
  Run run(std::size_t index) const;
  /// The base scenario with the run's overrides, resolved and checked (ConfigError if not).
  Scenario scenario(const Run& run) const;
  /// What defines the sweep (base and runs), as JSON: two plans with the same text make the
  /// same runs.
  std::string json() const;
  /// Whether `other` runs the same base scenario (file, workflow, profile): then runs of the
  /// two with one id are the same run.
  bool same_base(const Plan& other) const noexcept {
    return scenario_ == other.scenario_ && workflow_text_ == other.workflow_text_ && profile_ == other.profile_;
  }
  /// How to name the base on a `pcsim run` command line (the arguments before --set).
  std::string base_description() const;

 private:
  Scenario load_base(const std::vector<std::pair<std::string, std::string>>& overrides) const;
  void check_values(const std::vector<std::pair<std::size_t, std::string>>& where) const;

  std::string file_;
  std::string scenario_;       // absolute path, or empty
  std::string workflow_text_;  // a scenario TOML naming the workflow and platform, or empty
  std::string profile_;
  std::vector<std::string> keys_;
  std::vector<std::vector<Override>> axes_;  // per key, its values (grid)
  std::vector<std::vector<Override>> points_;  // or the explicit runs, each a value per key ("" toml: not set)
  std::size_t size_ = 0;
};

/// The id of a run with these overrides: 16 hex digits of a 64-bit FNV-1a hash of "key=value"
/// lines sorted by key.
std::string run_id(const std::vector<Override>& overrides);

}  // namespace pagecache::sweep
