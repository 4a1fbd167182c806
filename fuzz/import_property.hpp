#pragma once
// The import contract, checked by the workflow and platform fuzzers on every input their
// reader accepts: a scenario naming the file (a workflow on a fixed platform of two hosts, or a
// platform running one small application) reads or is refused with ConfigError, and what reads
// prints (pcsim show) as TOML that reads back the same (fuzz/scenario_property.hpp). The file
// is written where the scenario can name it: a file per process in the temporary folder.

#include "platform_property.hpp"
#include "scenario_property.hpp"
#include "workflow_property.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace pagecache::fuzz {

/// `text` written to a file of this process with `extension`; its path.
inline std::string temporary_input(const std::string& text, const std::string& extension) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("pcsim-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path.string();
}

/// A scenario source name beside the temporary inputs (their paths are absolute anyway).
inline std::string import_source_name() { return (std::filesystem::temp_directory_path() / "pcsim-fuzz-import.toml").string(); }

/// True if the workflow reader accepts `text` (within the fuzz limits).
inline bool reads_as_workflow(const std::string& text) {
  try {
    formats::wfformat::read_workflow_json(text, "fuzz.json", kFuzzMaxTasks, kFuzzMaxFiles);
    return true;
  } catch (const ConfigError&) {
    return false;
  }
}

/// True if the platform reader accepts `text` within the fuzz limits (30 hosts per cluster,
/// 100 in all): the import then lists at most a few thousand routes.
inline bool reads_as_small_platform(const std::string& text) {
  try {
    formats::simgrid::read_simgrid_platform(text, "fuzz.xml", fuzz_platform_limits());
    return true;
  } catch (const ConfigError&) {
    return false;
  }
}

/// "" if a workflow file of `text` keeps the import contract on two hosts joined by a link.
inline std::string check_workflow_import(const std::string& text) {
  const std::string path = temporary_input(text, ".json");
  const std::string scenario = R"(profile = "paper"
[[hosts]]
name = "h"
cores = 4
memory = "64 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "4 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[hosts]]
name = "g"
cores = 2
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "4 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[links]]
name = "l"
bandwidth = "1 GB/s"
hosts = ["h", "g"]
workflow = ")" + path + "\"\n";
  const std::string broken = check_scenario_text(scenario, import_source_name());
  return broken.empty() ? std::string() : "importing the workflow: " + broken;
}

/// "" if a platform file of `text` keeps the import contract, running one application that
/// reads a file of its first host, whatever the file says of the hosts' memory.
inline std::string check_platform_import(const std::string& text) {
  const std::string path = temporary_input(text, ".xml");
  const std::string scenario = "profile = \"paper\"\nplatform = \"" + path + R"("
[host_defaults]
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "4 GB/s"
[[files]]
name = "f"
size = "1 MB"
[[apps]]
[[apps.tasks]]
read = "f"
)";
  const std::string broken = check_scenario_text(scenario, import_source_name());
  return broken.empty() ? std::string() : "importing the platform: " + broken;
}

}  // namespace pagecache::fuzz
