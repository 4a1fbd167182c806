#pragma once
// Command lines for schedulers: `pcsim sweep plan --commands` (a line per shard, for GNU
// parallel, xargs -P or any scheduler) and `pcsim sweep slurm` (an sbatch script running the
// shards as a job array; each task finds its shard in Slurm's environment).

#include "sweep/sweep.hpp"

#include <cstddef>
#include <string>

namespace pagecache::sweep {

/// `text` as one word for a POSIX shell.
std::string shell_word(const std::string& text);

/// The `pcsim sweep run` command line of shard `index` of `shards`, one job in it.
std::string shard_command(const std::string& pcsim, const Sweep& plan, const std::string& out_dir, std::size_t index, std::size_t shards);

struct SlurmOptions {
  std::string pcsim;  ///< the pcsim to run, an absolute path
  std::string out_dir;
  std::size_t shards = 1;
  unsigned jobs = 1;  ///< runs at a time in each array task (its CPUs)
  std::string time;   ///< --time, as Slurm reads it (e.g. 01:00:00); empty: the partition's default
  std::string mem;    ///< --mem (e.g. 4G); empty: the default
  std::string partition;
  std::string job_name = "pcsim-sweep";
};

/// The script: `#SBATCH` directives for a job array of `shards` tasks, each running its shard
/// of the plan into out_dir (its log beside: slurm-JOB_TASK.out). Throws ConfigError for 0 shards
/// or a value that would break a directive (a line break, a space).
std::string sbatch_script(const Sweep& plan, const SlurmOptions& options);

}  // namespace pagecache::sweep
