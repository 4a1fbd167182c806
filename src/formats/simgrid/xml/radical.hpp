#pragma once
// A <cluster>'s radical, as SimGrid reads it: comma-separated numbers and ranges, "0-99" or
// "1,3,5-7", naming its nodes in that order.

#include <cstddef>
#include <string_view>
#include <vector>

namespace pagecache::formats::simgrid {

/// The numbers `text` names, in order. Each is a non-negative int; a range a-b needs a <= b.
/// Throws ConfigError (a short message quoting `text`) if `text` is malformed or names more
/// than `max_count` numbers, which is found before anything is allocated for them.
std::vector<int> parse_sg_radical(std::string_view text, std::size_t max_count);

}  // namespace pagecache::formats::simgrid
