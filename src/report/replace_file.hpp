#pragma once
// A file the user named (`pcsim validate --json FILE`), never left half-written: written to a
// temporary file in the same folder, then renamed over FILE. Replacing a file named explicitly
// is the point (as `gcc -o` does); a folder is refused, and a link is replaced, not written through.

#include <string>

namespace pagecache::report {

/// Throws ConfigError if `path` is a folder: before a long run, so that it is not wasted.
void check_output_file(const std::string& path);

/// Replaces `path` by a file holding `text`, with the permissions of the file it replaces (or
/// the umask's). Throws ConfigError if `path` is a folder, Error if it cannot be written.
void replace_file(const std::string& path, const std::string& text);

}  // namespace pagecache::report
