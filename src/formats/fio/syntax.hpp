#pragma once
// The lines of an fio job file (fio 3.33, init.c __parse_jobs_ini): comments, [sections],
// key=value options, include lines and ${VAR} substitution. What the options mean is
// formats/fio/options.hpp's business.

#include "formats/fio/job_file.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace pagecache::formats::fio {

/// One option line of a section, after ${VAR} substitution.
struct RawOption {
  std::string key;
  std::string value;  ///< "" for a bare key
  bool bare = false;  ///< written without '='
  std::string file;   ///< where it was written (an included file's own path)
  int line = 0;
  /// From an included file: messages name the option, never its value (the file may be
  /// anyone's, /etc/passwd included, and a message is no way to show it).
  bool included = false;
};

/// A name an option may have: letters, digits and '_'. A key of anything else is not an
/// option, and messages do not quote it (it is a line of some other file, not a misspelling).
bool option_shaped(std::string_view key);

/// A [section] and its option lines (an include's lines appended where it stood).
struct RawSection {
  std::string name;
  int line = 0;
  bool global = false;  ///< its name starts with "global", as fio decides
  std::vector<RawOption> options;
};

/// The sections of the job file text `text` read from `path`. Throws ConfigError naming
/// file:line for an option outside a section, whitespace around '=', a line longer than fio
/// reads, a malformed header, an include that cannot be read, nests too deep or in a cycle.
std::vector<RawSection> read_sections(std::string_view text, const std::string& path, const FioEnvironment& env,
                                      const FioLimits& limits);

/// `name` as "file:line: " for messages.
std::string where(const std::string& file, int line);

/// Throws ConfigError "file:line: message" placed at the option.
[[noreturn]] void fail(const RawOption& option, const std::string& message);

}  // namespace pagecache::formats::fio
