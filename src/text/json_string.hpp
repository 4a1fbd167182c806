#pragma once
// Strings in the JSON outputs (summary.json, pcsim validate --json).

#include <string>
#include <string_view>

namespace pagecache::text {

/// `s` as a JSON string literal, quotes included: `"` and `\` escaped, control characters below
/// 0x20 as \n, \t, ... or \u00XX, and each ill-formed UTF-8 part as U+FFFD (see utf8.hpp), so the
/// document is valid UTF-8 JSON whatever the bytes (a file path need not be UTF-8).
std::string json_string(std::string_view s);

}  // namespace pagecache::text
