#pragma once
// `pcsim sweep run`: the runs of one shard of a plan, `jobs` at a time in this process (each
// run single-threaded, so each is what `pcsim run` gives), each finished run appended to the
// shard's results file as one JSON line. Runs already in any results file of the folder are
// skipped, whatever shard split wrote them (a rerun resumes, a grown sweep runs only its new
// runs); a run that fails is recorded with its error and exit code, and the shard goes on.

#include "sweep/sweep.hpp"

#include <pagecache/run.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <unordered_set>

namespace pagecache::sweep {

/// Shard `index` of `count` (0 <= index < count) takes the runs whose index is `index` modulo
/// `count`.
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
};

/// "I/N". Throws ConfigError if it is not one.
Shard parse_shard(const std::string& text);
/// Under a Slurm job array: this task's shard (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of
/// SLURM_ARRAY_TASK_COUNT). Nothing outside an array.
std::optional<Shard> shard_from_slurm();

struct SweepOptions {
  std::string out_dir;
  Shard shard;
  unsigned jobs = 1;
  /// Also write each run's own output folder, out_dir/runs/ID (pcsim run's outputs, no report).
  bool keep_outputs = false;
  /// Called after each run with the runs finished and to do in this call (not thread-safe
  /// itself: called under the results' lock).
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct SweepOutcome {
  std::size_t ran = 0;
  std::size_t failed = 0;   ///< of those ran
  std::size_t skipped = 0;  ///< already in the results
  std::string results;      ///< the shard's results file
};

/// A finished run: its results line (result_line.hpp), and whether the run failed.
struct RunRecord {
  std::string line;
  bool failed = false;
};

/// One run of the plan, start to end, as `sweep run` makes it. A failure of the run (a value
/// its scenario refuses, the simulation stopped, memory exhausted) is the record's, with the
/// exit code `pcsim run` would give; an exception `run_options.progress` throws passes through
/// (a caller's way to stop a run). `outputs_dir`: also writes the run's outputs there, as
/// `--keep-outputs` does (and records the cache contents they hold).
RunRecord execute_run(const Sweep& plan, const Run& run, RunOptions run_options, const std::string& outputs_dir = {});

/// The file a shard writes: out_dir/results-I-of-N.jsonl.
std::string results_path(const std::string& out_dir, const Shard& shard);

/// Makes out_dir, checks what it holds, and writes its sweep-plan.json; returns the ids of the
/// runs its results files hold, of whatever shard split. A sweep-plan.json there already is
/// replaced if its base has the plan's fingerprint and every run it lists is one of this
/// plan's (the sweep grew: new axis values keep the old runs' ids, and their results stay
/// valid). Throws ConfigError, changing nothing, naming what differs in the base (a file
/// edited since, another file, another profile) or a run the plan would lose, or naming the
/// file and line of a results line that is not a result of this sweep (results_folder.hpp).
std::unordered_set<std::string> prepare_out_dir(const Sweep& plan, const std::string& out_dir);

/// prepare_out_dir, then runs the shard's runs that no results file of out_dir holds. Throws
/// ConfigError as prepare_out_dir and ResultsFile do; Error if the results cannot be written.
SweepOutcome run_sweep(const Sweep& plan, const SweepOptions& options);

}  // namespace pagecache::sweep
