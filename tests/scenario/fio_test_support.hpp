#pragma once
// Reading fio job file text in tests: with a fixed environment, and the ConfigError's message or
// place when the reader refuses it.

#include "formats/fio/job_file.hpp"

#include <pagecache/error.hpp>

#include <map>
#include <string>

namespace pagecache::scenario::testing {
using namespace pagecache::formats::fio;

/// The jobs of `text` read as "t.fio", ${VAR} looked up in `env`.
inline FioJobFile fio_read(const std::string& text, const std::map<std::string, std::string>& env = {}, const FioLimits& limits = {}) {
  return read_fio_job_file(
      text, "t.fio",
      [&env](const std::string& name) -> std::optional<std::string> {
        const auto found = env.find(name);
        if (found == env.end()) return std::nullopt;
        return found->second;
      },
      limits);
}

/// The message of the ConfigError reading `text` throws, or a text no test expects.
inline std::string fio_error(const std::string& text, const FioLimits& limits = {}) {
  try {
    fio_read(text, {}, limits);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(read without error)";
}

/// The place of the ConfigError reading `text` throws (empty if none).
inline InputPlace fio_place(const std::string& text) {
  try {
    fio_read(text);
  } catch (const ConfigError& error) {
    return error.place();
  }
  return {};
}

}  // namespace pagecache::scenario::testing
