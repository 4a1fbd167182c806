#pragma once
// Running the real pcsim binary (PCSIM_BINARY) as a user would, for the command-line tests:
// its exit status and output, and a small fast scenario.

#include "support/files.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

namespace pagecache::testing {

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
};

/// Runs `pcsim <args>` (args as a shell would split them), in the folder `cwd` if given.
inline Outcome pcsim(const std::string& args, const std::filesystem::path& cwd = {}) {
  const std::string in = cwd.empty() ? "" : fmt::format("cd '{}' && ", cwd.string());
  const std::string command = fmt::format("{}'{}' {} 2>&1 < /dev/null", in, PCSIM_BINARY, args);
  Outcome out;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) out.output.append(buffer.data(), n);
  const int raw = ::pclose(pipe);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

/// The number under `key` in the entry of `case_name` of pcsim validate's JSON.
inline double json_field(const std::string& json, const std::string& case_name, const std::string& key) {
  const auto at = json.find("\"case\": \"" + case_name + "\"");
  REQUIRE(at != std::string::npos);
  const auto k = json.find("\"" + key + "\": ", at);
  REQUIRE(k != std::string::npos);
  REQUIRE(k < json.find('}', at));
  return std::stod(json.substr(k + key.size() + 4));
}

/// One host with one disk, and one application reading one file: a run of a few milliseconds.
inline constexpr const char* kPlatform = R"(profile = "paper"
[[hosts]]
name = "h"
memory = "8 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "d"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
capacity = "10 GB"
)";

inline constexpr const char* kWorkload = R"(
[[files]]
name = "in"
size = "1 GB"
[[apps]]
name = "a"
[[apps.tasks]]
read = "in"
)";

}  // namespace pagecache::testing
