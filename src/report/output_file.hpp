#pragma once
// Every file pcsim writes under a name the user gave (`validate --json` and `--report`, `sweep
// merge --csv`, `calibrate --out`, the library's writers given a path), by one rule:
//   - absent, or a regular file: written beside it under a temporary name, then renamed over
//     it, so that it is never seen half-written; a replaced file keeps its permissions;
//   - a symbolic link to a regular file: that file is replaced so; the link stays a link;
//   - a character device or a FIFO (/dev/null, a named pipe), directly or through a link:
//     written through, as Unix tools do; /dev/stdout, /dev/stderr, /dev/fd/N and
//     /proc/self/fd/N are pcsim's own descriptors, written as they are;
//   - a folder, a link to nothing, a socket, a block device, or a path whose folder does not
//     exist: refused, with a ConfigError naming the option the path came from.
// A name up to the file system's limit works: the temporary name is short.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::report {

class RemovedOnInterrupt;

/// Throws ConfigError ("OPTION PATH: why", or "PATH: why" without an option) if `path` may not
/// receive an output now. Call it before long work, so that the work is not wasted.
void check_output_file(const std::string& path, std::string_view option = {});

/// Throws ConfigError ("OPTION PATH: is INPUT, which pcsim reads for this command; ...") if
/// writing `path` would replace one of the files `inputs` names (the same file, through a link
/// or not): an output never takes the place of what the command reads.
void check_not_an_input(const std::string& path, std::string_view option, const std::vector<std::string>& inputs);

/// An output written by the rule above, streamed: write() as often as needed, then commit().
/// Destroyed uncommitted (an error or an interruption on the way), it leaves nothing behind
/// but what a device or FIFO already received.
class OutputFile {
 public:
  /// Checks `path` (ConfigError as check_output_file) and opens it or its temporary file
  /// (Error if that fails).
  OutputFile(const std::string& path, std::string_view option = {});
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Throws ConfigError, naming the option, if the bytes cannot be written (a full disk).
  void write(std::string_view bytes);
  /// Puts the file in place (renames the temporary file over the target). Throws ConfigError
  /// naming the option if it cannot.
  void commit();

 private:
  std::string path_;     // as the user wrote it, for messages
  std::string option_;   // the option it came from, for messages ("" for none)
  std::string target_;   // the regular file to replace (a link's target), or empty: written through
  std::string temp_;     // the temporary file beside target_, while uncommitted
  int fd_ = -1;
  bool own_fd_ = true;   // false for pcsim's own stdout or stderr
  bool committed_ = false;
  std::unique_ptr<RemovedOnInterrupt> cleanup_;  // the temporary file, if interrupted
};

/// An OutputFile holding `text`, committed.
void write_output_file(const std::string& path, std::string_view text, std::string_view option = {});

}  // namespace pagecache::report
