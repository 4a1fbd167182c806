#pragma once
// `pcsim validate --here`: the paper's experiments run for real on this machine and scored
// against pcsim on its calibrated platform (src/validate/here.hpp); `--from` scores kept
// measurements again without any I/O.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace pcsim {

struct ValidateHereOptions {
  bool here = false;
  std::string dir;
  std::string platform;  ///< a calibrated platform file; empty: calibrate first
  std::string out = "pcsim-here";
  std::string from;
  int repeat = 0;  ///< 0: 3, or 1 with quick
  bool quick = false;
  std::vector<std::string> fio;  ///< fio job files: run them instead of the paper's experiments
  int fio_timeout = 600;         ///< fio's --timeout per run, seconds
  std::string memory_max;        ///< --fio: a size; fio in a memory cgroup of it, pcsim under it too
};

/// Adds the options to `validate`.
void add_validate_here_options(CLI::App& validate, ValidateHereOptions& options);
/// Throws ConfigError naming the options given to `validate` (parsed) that its mode does not
/// take, which would otherwise be ignored: --here's own (--dir, --platform, --out, --repeat,
/// --quick, --fio, --fio-timeout, --memory-max) without --here, --memory-max without --fio; with --here or --from, the comparison with the paper's data
/// (--json, --report, --profile, --set, --switch, --data, --scenarios); --here with --from.
void check_validate_mode(const CLI::App& validate);
class StatusLine;

/// Throws ConfigError unless --dir is a folder and --out is new (or an empty folder).
void check_here_folders(const ValidateHereOptions& options);
/// The platform's TOML: --platform's file, or a calibration of --dir (--quick: a quick one).
std::string here_platform_toml(const ValidateHereOptions& options, StatusLine& status);
/// Runs it; throws as the library does, returns the exit code otherwise.
int run_validate_here(const ValidateHereOptions& options);

}  // namespace pcsim
