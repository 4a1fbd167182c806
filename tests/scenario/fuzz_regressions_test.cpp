// Every input the scenario fuzzer (fuzz/) found to break the reader's contract is kept in
// tests/fuzz/regressions/, a file per bug, and replayed here through the same contract
// (fuzz/scenario_property.hpp): it reads, or it is refused with ConfigError, and what reads
// prints as TOML that reads back the same. Under the sanitizer build this catches what the
// fuzzer caught. Each runs in a watched child process: some asked for unbounded memory.

#include "support/watched_child.hpp"

#include "fio_property.hpp"
#include "import_property.hpp"
#include "platform_property.hpp"
#include "scenario_property.hpp"
#include "workflow_property.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace pagecache {
namespace {

// The inputs of one reader: .toml (scenario), .json (workflow), .xml (platform), .fio (fio job file).
std::vector<std::filesystem::path> regression_inputs(const char* extension = ".toml") {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(PAGECACHE_FUZZ_REGRESSIONS_DIR)) {
    if (entry.path().extension() == extension) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_CASE("every input the scenario fuzzer found reads, or is refused with ConfigError, and prints back the same",
          "[scenario][fuzz]") {
  const auto files = regression_inputs();
  REQUIRE_FALSE(files.empty());
  for (const auto& path : files) {
    const std::string text = read_file(path);
    const std::string failure = testing::run_watched([&] { return fuzz::check_scenario_text(text, path.string()); });
    INFO(path.filename().string() << ": " << failure);
    CHECK(failure.empty());
  }
}

TEST_CASE("every input the workflow, platform and fio fuzzers found reads, or is refused with ConfigError, and keeps the reader's promises",
          "[scenario][fuzz]") {
  for (const char* extension : {".json", ".xml", ".fio"}) {
    for (const auto& path : regression_inputs(extension)) {
      const std::string text = read_file(path);
      const std::string failure = testing::run_watched([&] {
        if (extension == std::string(".fio")) return fuzz::check_fio_text(text, path.string());
        const bool json = extension == std::string(".json");
        std::string broken = json ? fuzz::check_workflow_text(text, path.string()) : fuzz::check_platform_text(text, path.string());
        if (broken.empty() && (json ? fuzz::reads_as_workflow(text) : fuzz::reads_as_small_platform(text))) {
          broken = json ? fuzz::check_workflow_import(text) : fuzz::check_platform_import(text);
        }
        return broken;
      });
      INFO(path.filename().string() << ": " << failure);
      CHECK(failure.empty());
    }
  }
}

TEST_CASE("a watched child that keeps taking memory or time is killed, and one that crashes is reported", "[scenario][fuzz]") {
  const std::string hog = testing::run_watched(
      [] {
        std::vector<std::vector<char>> blocks;
        for (;;) blocks.emplace_back(std::size_t{1} << 20, 'x');
        return std::string();
      },
      {.resident_bytes = std::int64_t{64} << 20, .seconds = 60});
  CHECK(hog == "killed: grew by more than 64 MiB of resident memory");
  CHECK(testing::run_watched(
            []() -> std::string {
              for (;;) pause();
            },
            {.seconds = 1}) == "killed: still running after 1 s");
  CHECK(testing::run_watched([]() -> std::string { throw std::runtime_error("boom"); }).find("boom") != std::string::npos);
  CHECK(testing::run_watched([] { return std::string("broken"); }) == "broken");
  CHECK(testing::run_watched([] { return std::string(); }).empty());
  CHECK(testing::run_watched([]() -> std::string { _exit(3); }) == "crashed: exit status 3 (its report is above)");
}

}  // namespace
}  // namespace pagecache
