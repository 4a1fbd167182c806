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
// the axes, renames no run. What the runs share, the base, has its own fingerprint
// (base_identity.hpp): a run is its id under its base's fingerprint.

#include "sweep/base_identity.hpp"

#include <pagecache/scenario_file.hpp>

#include <cstdint>
#include <functional>
#include <optional>
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
  std::vector<Override> overrides;  ///< in the order of Sweep::keys
};

/// Above this many runs a sweep needs --force (ten million: a day of small runs on 100 cores).
inline constexpr double kMaxRuns = 1e7;
/// The most values one axis may have, --force or not (each is held in memory).
inline constexpr double kMaxAxisValues = 1e7;
/// The most runs pcsim numbers, --force or not.
inline constexpr double kMaxNumberedRuns = 1e12;

/// How much a sweep file may ask for before any value is made.
struct SweepLimits {
  double runs = kMaxRuns;  ///< without --force
  double axis_values = kMaxAxisValues;
  /// What the base, tried with each axis value, may ask of a scenario.
  ScenarioLimits scenario;
};

class Sweep {
 public:
  /// Reads the sweep file. Throws ConfigError naming the file, line and axis of the first
  /// problem: an unknown key, an empty axis, a range whose step or factor is 0, not a finite
  /// number, or never reaches its end, a value twice on one axis, two identical points, a
  /// value of the wrong type for its key (each axis value is tried on the base scenario), an
  /// axis of more than kMaxAxisValues values, more than kMaxRuns runs without `force`. Axis
  /// lengths and the grid's size are computed, and checked, before any value is made.
  /// `checkpoint`, if set, is called before each value or point is tried on the base (a large
  /// base takes a while to resolve): what it throws passes through, which is how a caller
  /// stops a long check.
  static Sweep load(const std::string& path, bool force = false, const std::function<void()>& checkpoint = {});
  /// The same from the sweep file's text; `path` places the files it names and is named in
  /// messages.
  static Sweep parse(const std::string& text, const std::string& path, bool force = false, const SweepLimits& limits = {},
                    const std::function<void()>& checkpoint = {});
  /// The plan json() wrote (`origin` names it in errors). Throws ConfigError if it is not one,
  /// or is one of an earlier pcsim, which recorded no fingerprint of its base.
  static Sweep from_json(const std::string& text, const std::string& origin);

  const std::string& file() const noexcept { return file_; }
  /// The keys the runs override, in the sweep file's order: the axes of results.csv.
  const std::vector<std::string>& keys() const noexcept { return keys_; }
  std::size_t size() const noexcept { return size_; }
  Run run(std::size_t index) const;
  /// The index of the run with these overrides (key, TOML value; a key a point leaves unset is
  /// absent), if the plan has it: a result recorded under an earlier plan of a grown sweep is
  /// found by its values. A value is looked for along its axis (or the points), not the grid.
  std::optional<std::size_t> index_of(const std::vector<std::pair<std::string, std::string>>& overrides) const;
  /// The base scenario with the run's overrides, resolved and checked (ConfigError if not).
  Scenario scenario(const Run& run) const;
  /// What defines the sweep (base, with its files' hashes and fingerprint, and runs), as JSON:
  /// two plans with the same text make the same runs.
  std::string json() const;
  /// The base, as read when the plan was made: runs of two plans with one fingerprint and
  /// one id are the same run.
  const BaseIdentity& base() const noexcept { return base_; }
  const std::string& fingerprint() const noexcept { return fingerprint_; }
  /// The values held in memory: the axes' (or the points'), whatever the number of runs.
  std::size_t values_held() const noexcept;
  /// How to name the base on a `pcsim run` command line (the arguments before --set).
  std::string base_description() const;

 private:
  Scenario load_base(const std::vector<std::pair<std::string, std::string>>& overrides, const ScenarioLimits& limits = {}) const;
  void check_values(const std::vector<std::pair<std::size_t, std::string>>& where, const ScenarioLimits& limits,
                    const std::function<void()>& checkpoint) const;

  std::string file_;
  std::string scenario_;       // absolute path, or empty
  std::string workflow_text_;  // a scenario TOML naming the workflow and platform, or empty
  std::string profile_;
  std::vector<std::string> keys_;
  std::vector<std::vector<Override>> axes_;  // per key, its values (grid)
  std::vector<std::vector<Override>> points_;  // or the explicit runs, each a value per key ("" toml: not set)
  std::size_t size_ = 0;
  BaseIdentity base_;
  std::string fingerprint_;
};

/// The id of a run with these overrides: 16 hex digits of a 64-bit FNV-1a hash of "key=value"
/// lines sorted by key.
std::string run_id(const std::vector<Override>& overrides);

}  // namespace pagecache::sweep
