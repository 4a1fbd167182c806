#pragma once
// `pcsim sweep merge DIR`: the shards' results in one results.csv, a row per run in the plan's
// order (a column per swept key, then the figures), the same whichever way the runs were
// spread over shards, processes and machines, but for the wall times.

#include <cstddef>
#include <string>
#include <vector>

namespace pagecache::sweep {

class Sweep;

struct MergeOptions {
  std::string dir;
  std::string csv;  ///< default: DIR/results.csv
  /// Merge what is there; otherwise missing runs are an error.
  bool allow_missing = false;
};

struct MergeOutcome {
  std::size_t runs = 0;     ///< rows written
  std::size_t missing = 0;  ///< runs of the plan without a result
  std::size_t failed = 0;   ///< rows of failed runs
  std::string csv;
};

/// Throws ConfigError naming the missing (unless allowed) or duplicated runs, a result that is
/// not of the plan's runs, a line that is not a result of the plan's base (file and line), a
/// results file pcsim did not make, a DIR without a sweep-plan.json, or a --csv that cannot
/// receive the CSV ("--csv PATH: is a folder", checked first) or is one of the files merge
/// reads (sweep-plan.json, a results file).
MergeOutcome merge(const MergeOptions& options);

/// results.csv's text for runs made in memory: `lines[i]` is run i's results line (one per
/// run of `plan`, in its order), as execute_run made it. The rows merge would write for them.
std::string results_csv(const Sweep& plan, const std::vector<std::string>& lines);

}  // namespace pagecache::sweep
