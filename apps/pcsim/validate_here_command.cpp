#include "validate_here_command.hpp"

#include "calibrate/calibrate.hpp"
#include "calibrate/measure.hpp"
#include "calibrate/real_run.hpp"
#include "calibrate/system_info.hpp"
#include "status_line.hpp"
#include "validate/fio_kept.hpp"
#include "validate/here.hpp"
#include "validate_fio_command.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

namespace pcsim {

namespace fs = std::filesystem;

void add_validate_here_options(CLI::App& validate_app, ValidateHereOptions& o) {
  CLI::App* validate = &validate_app;
  validate->add_flag("--here", o.here,
                     "run the paper's experiments for real on this machine (three Exp-1-like sizes, Exp-2-like 4 and 8 pipelines) and score "
                     "pcsim against them on the machine's calibrated platform");
  validate->add_option("--dir", o.dir, "--here: the folder whose file system the real runs use (their files are removed)");
  validate->add_option("--platform", o.platform, "--here: a platform file from pcsim calibrate (default: calibrate first)");
  validate->add_option("--out", o.out, "--here: a new folder for the measurements and the report (an existing one is refused, never replaced)")
      ->capture_default_str();
  validate->add_option("--from", o.from, "score the measurements kept in this folder by an earlier --here again, without running anything");
  validate->add_option("--repeat", o.repeat, "--here: repetitions of each case (default 3, 1 with --quick)")->check(CLI::Range(1, 100));
  validate->add_option("--fio", o.fio,
                       "--here: fio job files to run with the real fio (in a fresh folder inside --dir) and to score pcsim's bandwidth "
                       "against, instead of the paper's experiments");
  validate->add_option("--fio-timeout", o.fio_timeout, "--here --fio: fio's --timeout for each run, in seconds (a job pcsim estimates longer is refused)")
      ->capture_default_str()
      ->check(CLI::Range(1, 86400));
  validate->add_option("--memory-max", o.memory_max,
                       "--here --fio: run each fio in a memory cgroup of this limit (\"256 MiB\"; pcsim makes it and removes it after: root) "
                       "and simulate each job file under it ([fio] memory_max)");
  validate->add_flag("--quick", o.quick, "--here: tiny cases, one repetition, a quick calibration: proves the pipeline works, measures little");
}

namespace {

std::string read_text(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw pagecache::ConfigError(fmt::format("{} '{}': cannot read", what, path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void check_validate_mode(const CLI::App& validate) {
  const bool here = validate.count("--here") > 0;
  const bool from = validate.count("--from") > 0;
  if (here && from) throw pagecache::ConfigError("validate: --here runs the experiments, --from scores those kept in a folder: give one");
  const auto refuse = [&](std::initializer_list<const char*> options, std::string_view why) {
    std::vector<std::string> given;
    for (const char* name : options)
      if (validate.count(name) > 0) given.emplace_back(name);
    if (!given.empty()) {
      throw pagecache::ConfigError(fmt::format("validate: {} {} {}", fmt::join(given, ", "), given.size() == 1 ? "is an option" : "are options", why));
    }
  };
  if (here || from) {
    refuse({"--json", "--report", "--profile", "--set", "--switch", "--data", "--scenarios"},
           fmt::format("of the comparison with the paper's data, which {} does not make: it scores this machine's runs on their "
                       "calibrated platform and prints the table{}",
                       here ? "--here" : "--from", here ? " (also into --out's report.txt)" : ""));
  }
  if (!here) {
    refuse({"--dir", "--platform", "--out", "--repeat", "--quick", "--fio", "--fio-timeout", "--memory-max"},
           from ? "of --here: --from scores the folder it names again, running nothing" : "of --here (the experiments run for real here)");
  } else if (validate.count("--fio") == 0) {
    refuse({"--memory-max"}, "of --here --fio: the paper's experiments run without a memory cgroup of pcsim's");
  }
}

void check_here_folders(const ValidateHereOptions& o) {
  if (o.dir.empty()) throw pagecache::ConfigError("validate --here needs --dir: a folder on the file system to run in");
  std::error_code ec;
  if (!fs::is_directory(o.dir, ec)) throw pagecache::ConfigError(fmt::format("--dir '{}': not a folder", o.dir));
  if (fs::exists(fs::symlink_status(o.out, ec)) && !(fs::is_directory(o.out, ec) && fs::is_empty(o.out, ec))) {
    throw pagecache::ConfigError(fmt::format("--out '{}': exists; measurements go into a new folder (pcsim never replaces them)", o.out));
  }
}

std::string here_platform_toml(const ValidateHereOptions& o, StatusLine& status) {
  namespace cal = pagecache::calibrate;
  if (!o.platform.empty()) return read_text(o.platform, "--platform");
  cal::Options options;
  options.dir = o.dir;
  options.quick = o.quick;
  options.progress = [&](const std::string& step, int number, int steps) {
    if (status.due(true)) status.show(fmt::format("calibrate: {}/{} {}", number, steps, step));
  };
  const cal::Calibration c = cal::calibrate(options);
  status.clear();
  fmt::print("calibrated in {:.0f} s\n", c.seconds);
  return cal::platform_toml(c);
}

int run_validate_here(const ValidateHereOptions& o) {
  namespace cal = pagecache::calibrate;
  namespace val = pagecache::validate;
  if (!o.from.empty()) {
    if (val::is_fio_folder(o.from)) return score_validate_fio(o.from);
    fmt::print("{}", val::score_here(val::load_here(o.from)));
    return 0;
  }
  if (!o.fio.empty()) return run_validate_fio(o);
  check_here_folders(o);
  cal::install_stop_handlers();
  StatusLine status(true);
  val::HereMeasurements m;
  m.platform_toml = here_platform_toml(o, status);
  const cal::SystemInfo sys = cal::read_system_info(o.dir);
  const std::vector<cal::RealCase> cases = val::here_cases(sys.memory_available, o.quick);
  std::int64_t need = 0;
  for (const cal::RealCase& c : cases) need = std::max(need, static_cast<std::int64_t>(c.pipelines) * (c.tasks + 1) * c.file_size);
  if (sys.file_system_free < need) {
    throw pagecache::ConfigError(fmt::format("--dir '{}': its file system has {} MB free; the largest case writes {} MB there", o.dir,
                                             sys.file_system_free / 1'000'000, need / 1'000'000));
  }
  const int repeat = o.repeat > 0 ? o.repeat : (o.quick ? 1 : 3);
  const int total = static_cast<int>(cases.size()) * repeat;
  int done = 0;
  for (const cal::RealCase& c : cases) {
    for (int rep = 1; rep <= repeat; ++rep) {
      ++done;
      if (status.due(true)) status.show(fmt::format("validate --here: run {}/{}: {} (repetition {})", done, total, c.name, rep));
      m.runs.push_back(cal::run_real(c, o.dir, rep, o.quick ? 0.05 : 0.25, o.quick ? 6.0 : 40.0));
    }
  }
  status.clear();
  // Kept first, then scored from what was kept: `validate --from` gives the same table.
  fs::create_directories(o.out);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream out(fs::path(o.out) / name, std::ios::binary);
    out << text;
    if (!out) throw pagecache::Error(fmt::format("cannot write {}", (fs::path(o.out) / name).string()));
  };
  for (const auto& [name, text] : val::here_files(m)) write(name, text);
  const std::string report = val::score_here(val::load_here(o.out));
  write("report.txt", report);
  fmt::print("{}measurements and report: {} (score them again: pcsim validate --from {})\n", report, o.out, o.out);
  return 0;
}

}  // namespace pcsim
