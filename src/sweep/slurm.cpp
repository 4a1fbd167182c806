#include "sweep/slurm.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::sweep {

std::string shell_word(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '/' || c == '.' || c == '_' || c == '-' || c == '+' || c == ':' || c == '=' || c == ',';
  });
  if (plain) return text;
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string shard_command(const std::string& pcsim, const Sweep& plan, const std::string& out_dir, std::size_t index, std::size_t shards) {
  return fmt::format("{} sweep run {} --out {} --shard {}/{} --jobs 1", shell_word(pcsim), shell_word(plan.file()), shell_word(out_dir), index, shards);
}

std::string sbatch_script(const Sweep& plan, const SlurmOptions& o) {
  if (o.shards == 0) throw ConfigError("--shards must be at least 1");
  const auto directive = [](const char* option, const std::string& value) {
    if (value.find_first_of(" \t\r\n") != std::string::npos) throw ConfigError(fmt::format("--{} '{}': no spaces or line breaks", option, value));
    return fmt::format("#SBATCH --{}={}\n", option, value);
  };
  std::string out = "#!/bin/bash\n";
  out += fmt::format("# pcsim sweep {}: {} runs in {} array tasks of {} run(s) at a time.\n", plan.file(), plan.size(), o.shards, o.jobs);
  out += fmt::format("# Submit with sbatch; when every task is done: {} sweep merge {}\n", shell_word(o.pcsim), shell_word(o.out_dir));
  out += directive("job-name", o.job_name);
  out += directive("array", fmt::format("0-{}", o.shards - 1));
  out += directive("ntasks", "1");
  out += directive("cpus-per-task", std::to_string(o.jobs));
  out += directive("output", o.out_dir + "/slurm-%A_%a.out");
  if (!o.time.empty()) out += directive("time", o.time);
  if (!o.mem.empty()) out += directive("mem", o.mem);
  if (!o.partition.empty()) out += directive("partition", o.partition);
  // The shard comes from SLURM_ARRAY_TASK_ID and the array's size; a task run again resumes.
  out += fmt::format("exec {} sweep run {} --out {} --jobs {}\n", shell_word(o.pcsim), shell_word(plan.file()), shell_word(o.out_dir), o.jobs);
  return out;
}

}  // namespace pagecache::sweep
