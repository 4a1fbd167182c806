#pragma once
// Reading a scenario or platform file whole, refusing what is not one: a device such as
// /dev/zero would be read for ever, a FIFO would block for ever, and a huge file would be
// held in memory before a single key is checked.

#include <cstdint>
#include <string>
#include <string_view>

namespace pagecache::formats {

/// The largest scenario or platform file read: 64 MiB (the biggest shipped is a few kB; a
/// workflow of 10^5 tasks written out in full is about 20 MB).
inline constexpr std::int64_t kMaxTextFileBytes = std::int64_t{64} << 20;

/// The contents of the regular file `path`. Throws ConfigError naming the file and `what` it
/// was to be ("scenario file", "platform file") if its name holds a NUL, it cannot be opened,
/// is not a regular file or is larger than kMaxTextFileBytes.
std::string read_text_file(const std::string& path, const char* what);

/// The same checks without reading, for a file named on the command line before pcsim builds
/// anything around it: the ConfigError names `argument` (an option such as "--platform", or
/// "" for a positional argument, whose path is its name) and the path.
void check_text_file(std::string_view argument, const std::string& path, const char* what);

}  // namespace pagecache::formats
