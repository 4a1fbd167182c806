#pragma once
// JSON text to a document (nlohmann::json), for the readers of JSON inputs: malformed text is
// refused with the line and column of the fault, and nesting deeper than any input format
// needs is refused before a document is built (a file of 64 MiB of '[' would otherwise take
// gigabytes as nested arrays).

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace pagecache::formats {

/// The deepest nesting of arrays and objects read: WfFormat needs 6 (command.arguments), and
/// unknown keys get room to spare.
inline constexpr std::size_t kMaxJsonDepth = 128;

/// "LINE:COL" of byte `offset` of `text`: lines from 1, columns from 1 in characters (UTF-8
/// code points) so that an editor finds them; an offset past the end names the end.
std::string line_column(std::string_view text, std::size_t offset);

/// The document `text` holds. Throws ConfigError "FILE:LINE:COL: malformed JSON: WHAT" for
/// text that is not JSON (including numbers beyond a double, such as 1e400), and
/// "FILE:LINE:COL: JSON nested deeper than ..." at the first bracket past kMaxJsonDepth.
/// Also "FILE:LINE:COL: key K appears twice in one object" (check_unique_keys).
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

/// Throws ConfigError "FILE:LINE:COL: key K appears twice in one object ..." at the second of
/// two equal keys (compared as decoded: "\u006e" is "n") of one object of `text`, valid JSON:
/// parsers differ on which one wins, so pcsim's readers take neither. Every reader of JSON
/// input calls it.
void check_unique_keys(std::string_view text, const std::string& file);

}  // namespace pagecache::formats
