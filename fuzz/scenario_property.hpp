#pragma once
// The scenario reader's contract, as fuzz/scenario_fuzzer.cpp checks it on every input and
// tests/scenario/fuzz_regressions_test.cpp replays it on the inputs the fuzzer found: any text
// either reads as a scenario or is refused with ConfigError (bad input); any other exception,
// a crash, a hang, unbounded memory or a sanitizer report is a bug. A scenario that reads is
// printed by to_toml (`pcsim show`) as TOML that reads back to a scenario printed the same.

#include <pagecache/error.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace pagecache::fuzz {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The line (from 1) that a ConfigError's "<source>:<line>:<column>: ..." names, or 0.
inline std::size_t error_line(const std::string& message, const std::string& source_name) {
  if (message.compare(0, source_name.size() + 1, source_name + ":") != 0) return 0;
  std::size_t line = 0;
  for (std::size_t i = source_name.size() + 1; i < message.size() && message[i] >= '0' && message[i] <= '9'; ++i) {
    line = line * 10 + static_cast<std::size_t>(message[i] - '0');
  }
  return line;
}

/// The limits inputs are read with: the defaults let a scenario of 10^6 tasks through, which
/// takes seconds to build (more under the sanitizers) and would stall the search; the checks
/// that enforce them are the same.
inline ScenarioLimits fuzz_limits() {
  ScenarioLimits limits;
  limits.max_tasks = 10'000;
  limits.max_files = 20'000;
  return limits;
}

/// "" if `text` keeps the contract, else what broke. Exceptions other than ConfigError are
/// not caught: in the fuzzer they end the process where they were thrown (the stack shows
/// the throw), in a test Catch2 reports them.
inline std::string check_scenario_text(const std::string& text, const std::string& source_name) {
  Scenario scenario;
  try {
    scenario = parse_scenario(text, source_name, {}, {}, fuzz_limits());
  } catch (const ConfigError&) {
    return {};
  }
  const std::vector<std::string> printed = lines_of(to_toml(scenario));
  Scenario again;
  try {
    again = parse_scenario(to_toml(scenario), source_name, {}, {}, fuzz_limits());
  } catch (const ConfigError& e) {
    const std::size_t line = error_line(e.what(), source_name);
    return std::string("to_toml's output does not read back: ") + e.what() +
           (line >= 1 && line <= printed.size() ? "\n  that line: " + printed[line - 1] : std::string());
  }
  // Line 1 names the source, the same for both.
  const std::vector<std::string> reprinted = lines_of(to_toml(again));
  for (std::size_t i = 1; i < printed.size() || i < reprinted.size(); ++i) {
    const std::string before = i < printed.size() ? printed[i] : "(none)";
    const std::string after = i < reprinted.size() ? reprinted[i] : "(none)";
    if (before != after) {
      return "to_toml's output reads back to a different scenario: its line " + std::to_string(i + 1) + ", " + before +
             ", prints back as " + after;
    }
  }
  return {};
}

}  // namespace pagecache::fuzz
