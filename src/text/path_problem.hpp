#pragma once
// A path the user gave and what went wrong with it, named the one way every command names it:
// the option or argument it came from, the path as printable() shows it (a NUL or a control
// character visible), then why. Each layer throws its ConfigError (exit 2) with this text, so
// that a file system error on a user's path says which argument to fix, never a raw
// "filesystem error: ...".

#include <string>
#include <string_view>
#include <system_error>

namespace pagecache::text {

/// "ARGUMENT PATH: WHY", or "PATH: WHY" for an empty `argument` (a positional file argument,
/// whose path is its name).
std::string path_message(std::string_view argument, std::string_view path, std::string_view why);

/// path_message with WHY "WHAT: the error's message" (or the message alone for an empty `what`).
std::string path_message(std::string_view argument, std::string_view path, std::string_view what, std::error_code error);

/// Why `path` cannot name a file: it holds a NUL byte (a C string ends there, so the file
/// named would be another one). Empty if it can.
std::string nul_problem(std::string_view path);

}  // namespace pagecache::text
