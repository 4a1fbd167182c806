#include "sweep_command.hpp"

#include "status_line.hpp"

#include "report/output_file.hpp"
#include "sweep/executor.hpp"
#include "sweep/merge.hpp"
#include "sweep/sweep.hpp"
#include "sweep/slurm.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <unistd.h>

namespace pcsim {

namespace {

namespace fs = std::filesystem;
using namespace pagecache;

// This pcsim, as an absolute path for command lines other processes and machines run.
std::string self() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("pcsim") : exe.string();
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// On a terminal: runs done of this call's, their rate and the time left, at most five times a
// second, on one line of stderr.
class SweepProgress {
 public:
  explicit SweepProgress(bool enabled) : line_(enabled) {}
  void update(std::size_t done, std::size_t total) {
    if (const auto wall = line_.due(done == total)) {
      const double rate = *wall > 0 ? static_cast<double>(done) / *wall : 0.0;
      const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
      line_.show(fmt::format("{} of {} runs, {:.1f} runs/s, {:.0f} s left", done, total, rate, left));
    }
  }
  void clear() { line_.clear(); }

 private:
  StatusLine line_;
};

}  // namespace

void add_sweep_command(CLI::App& app, SweepCommand& c) {
  c.sweep = app.add_subcommand("sweep", "many runs of one scenario: plan them, run them (here, with GNU parallel or Slurm), merge them");
  c.sweep->require_subcommand(1);
  const char* force_help = "a sweep of more than 10^7 runs";

  c.plan = c.sweep->add_subcommand("plan", "list the sweep's runs (id and overrides), or with --commands a command line per shard");
  c.plan->add_option("sweep", c.file, "sweep file (TOML)")->required();
  c.plan->add_flag("--commands", c.commands, "print one `pcsim sweep run` command line per shard (for parallel, xargs -P, any scheduler)");
  c.plan->add_option("--shards", c.shards, "with --commands: this many shards (default: one per run)");
  c.plan->add_option("--out", c.out, "with --commands: the folder the commands write their results to");
  c.plan->add_flag("--force", c.force, force_help);

  c.run = c.sweep->add_subcommand("run", "run a shard of the sweep, appending a JSON line per run to OUT/results-I-of-N.jsonl; a rerun resumes");
  c.run->add_option("sweep", c.file, "sweep file (TOML)")->required();
  c.run->add_option("--out", c.out, "results folder (made if absent; it holds sweep-plan.json and the shards' results)")->required();
  c.run->add_option("--shard", c.shard, "run shard I of N (0 <= I < N): the runs whose index is I modulo N (default: from a Slurm job array, else 0/1)");
  c.run->add_option("--jobs", c.jobs, "runs at a time, each on a thread of this process")->capture_default_str()->check(CLI::Range(1u, 1024u));
  c.run->add_flag("--keep-outputs", c.keep_outputs, "also write each run's outputs to OUT/runs/ID (as pcsim run, without report.html)");
  c.run->add_flag("--quiet", c.quiet, "print nothing but errors");
  c.run->add_flag("--force", c.force, force_help);

  c.slurm = c.sweep->add_subcommand("slurm", "print an sbatch script that runs the sweep as a Slurm job array (makes OUT and its sweep-plan.json)");
  c.slurm->add_option("sweep", c.file, "sweep file (TOML)")->required();
  c.slurm->add_option("--out", c.out, "results folder, on a file system the nodes share")->required();
  c.slurm->add_option("--shards", c.shards, "array tasks")->required()->check(CLI::Range(std::size_t{1}, std::size_t{1000000}));
  c.slurm->add_option("--jobs", c.jobs, "runs at a time in each task (its CPUs)")->capture_default_str()->check(CLI::Range(1u, 1024u));
  c.slurm->add_option("--time", c.time, "each task's time limit, as sbatch reads it (e.g. 01:00:00)");
  c.slurm->add_option("--mem", c.mem, "each task's memory, as sbatch reads it (e.g. 4G)");
  c.slurm->add_option("--partition", c.partition, "the partition");
  c.slurm->add_flag("--force", c.force, force_help);

  c.merge = c.sweep->add_subcommand("merge", "merge the shards' results into one CSV: a row per run, a column per swept key, then the figures");
  c.merge->add_option("dir", c.out, "the results folder")->required();
  c.merge->add_option("--csv", c.csv, "where to write (default: DIR/results.csv)");
  c.merge->add_flag("--allow-missing", c.allow_missing, "merge the runs that have results, leaving out the others");
}

int run_sweep_command(const SweepCommand& c) {
  if (c.merge->parsed()) {
    if (c.merge->count("--csv") > 0) pagecache::report::check_output_file(c.csv, "--csv");  // `--csv ''` is refused, not ignored
    const sweep::MergeOutcome m = sweep::merge({c.out, c.csv, c.allow_missing});
    fmt::print("{}: {} runs{}{}\n", m.csv, m.runs, m.failed ? fmt::format(", {} failed", m.failed) : "",
               m.missing ? fmt::format(", {} missing", m.missing) : "");
    return 0;
  }
  const sweep::Sweep plan = sweep::Sweep::load(c.file, c.force);
  if (c.plan->parsed()) {
    if (c.commands) {
      if (c.out.empty()) throw ConfigError("sweep plan --commands: --out DIR names where the commands write their results");
      const std::size_t shards = c.shards == 0 ? plan.size() : c.shards;
      if (shards > plan.size()) throw ConfigError(fmt::format("--shards {}: the sweep has {} runs", shards, plan.size()));
      for (std::size_t i = 0; i < shards; ++i) fmt::print("{}\n", sweep::shard_command(self(), plan, absolute(c.out), i, shards));
      return 0;
    }
    for (std::size_t i = 0; i < plan.size(); ++i) {
      const sweep::Run run = plan.run(i);
      std::string line = run.id;
      for (const sweep::Override& o : run.overrides)
        if (!o.toml.empty()) line += " " + sweep::shell_word(o.key + "=" + o.toml);
      fmt::print("{}\n", line);
    }
    return 0;
  }
  if (c.slurm->parsed()) {
    sweep::SlurmOptions o;
    o.pcsim = self();
    o.out_dir = absolute(c.out);
    o.shards = c.shards;
    o.jobs = c.jobs;
    o.time = c.time;
    o.mem = c.mem;
    o.partition = c.partition;
    const std::string script = sweep::sbatch_script(plan, o);
    sweep::prepare_out_dir(plan, o.out_dir);
    fmt::print("{}", script);
    return 0;
  }
  sweep::SweepOptions o;
  o.out_dir = c.out;
  o.jobs = c.jobs;
  o.keep_outputs = c.keep_outputs;
  if (!c.shard.empty()) o.shard = sweep::parse_shard(c.shard);
  else if (const auto from_slurm = sweep::shard_from_slurm()) o.shard = *from_slurm;
  SweepProgress progress(!c.quiet);
  o.progress = [&progress](std::size_t done, std::size_t total) { progress.update(done, total); };
  sweep::SweepOutcome outcome;
  try {
    outcome = sweep::run_sweep(plan, o);
  } catch (...) {
    progress.clear();
    throw;
  }
  progress.clear();
  if (!c.quiet) {
    fmt::print("shard {}/{}: {} runs done ({} failed), {} already there; results: {}\n", o.shard.index, o.shard.count, outcome.ran, outcome.failed,
               outcome.skipped, outcome.results);
  }
  return 0;
}

}  // namespace pcsim
