#pragma once
// Suggesting what a user meant: the known word closest to a misspelt one (a scenario key,
// a command).

#include <set>
#include <string>
#include <string_view>

namespace pagecache::formats {

/// The candidate closest to `typed` by edit distance (transpositions count one), if close
/// enough to be a typo of it: at most two edits, and at most a third of the word; else "".
std::string closest(std::string_view typed, const std::set<std::string>& candidates);

}  // namespace pagecache::formats
