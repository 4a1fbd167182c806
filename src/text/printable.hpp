#pragma once
// Names shown to a person (the summary on a terminal, the comment atop `pcsim show`): nothing
// in a name may move the cursor, clear the screen, end a line or reorder the text around it.

#include <string>
#include <string_view>

namespace pagecache::text {

/// `s` with control characters (C0, DEL, C1), line and paragraph separators and bidirectional
/// controls written visibly (\n, \r, \t, else \u001b-style escapes) and each ill-formed UTF-8
/// part as U+FFFD; anything else as is. For display only: a backslash is not escaped.
std::string printable(std::string_view s);

}  // namespace pagecache::text
