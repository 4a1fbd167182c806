#pragma once
// `pcsim sweep plan|run|slurm|merge`: the command line of parameter sweeps (src/sweep/).

#include <CLI/CLI.hpp>

#include <string>

namespace pcsim {

struct SweepCommand {
  CLI::App* sweep = nullptr;
  CLI::App* plan = nullptr;
  CLI::App* run = nullptr;
  CLI::App* slurm = nullptr;
  CLI::App* merge = nullptr;
  std::string file;
  std::string out;
  std::string shard;
  std::string csv;
  std::string time, mem, partition;
  unsigned jobs = 1;
  std::size_t shards = 0;
  bool commands = false;
  bool force = false;
  bool keep_outputs = false;
  bool allow_missing = false;
  bool quiet = false;
};

/// Adds `sweep` and its four commands to `app`; their options land in `command`.
void add_sweep_command(CLI::App& app, SweepCommand& command);
/// Runs the sweep command that was parsed. Throws as the library does (main maps errors to
/// exit codes); returns the exit code otherwise.
int run_sweep_command(const SweepCommand& command);

}  // namespace pcsim
