#pragma once
// `pcsim calibrate`: the command line of the machine's measurement (src/calibrate/).

#include <CLI/CLI.hpp>

#include <string>

namespace pcsim {

struct CalibrateCommand {
  CLI::App* app = nullptr;
  std::string dir;
  std::string out;
  std::string size;
  int streams = 0;
  int repeat = 0;
  bool quick = false;
};

/// Adds `calibrate` to `app`; its options land in `command`.
void add_calibrate_command(CLI::App& app, CalibrateCommand& command);
/// Runs it. Throws as the library does (main maps errors to exit codes); returns the exit
/// code otherwise.
int run_calibrate_command(const CalibrateCommand& command);

}  // namespace pcsim
