#pragma once
// A shard's results: one JSON line per finished run, appended (result_line.hpp). Each line goes
// to the file in one write() on a descriptor opened O_APPEND, so that a shard killed at any
// moment leaves whole lines and at most a partial last one. The file is locked (flock) while a
// shard writes it: a second process on the same shard is refused instead of interleaving.
//
// Read before write: a results file is checked whole before pcsim changes a byte of it. Only a
// file pcsim made is changed (a regular file of one name: not a link, a hard link, a device),
// and the one repair, dropping a last line without its newline, is made only if that line is
// the beginning of a result pcsim wrote. Anything else is refused, the file left as it is.

#include <cstddef>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::sweep {

/// What a results file's bytes hold.
struct ResultsText {
  struct Line {
    std::string id;
    std::size_t number = 0;  ///< from 1
    std::string_view text;   ///< without its newline, into the text read
  };
  std::vector<Line> lines;  ///< the whole lines, each a result of the sweep
  std::size_t whole = 0;    ///< bytes of the whole lines; after them, a last line cut short (pcsim's)
};

/// Checks every line of `text`, a results file's bytes (`name` in messages), as results of the
/// sweep whose base has `fingerprint`. Throws ConfigError "NAME:LINE: ..." at the first line
/// that is not one, or a last line without its newline that is not the beginning of one.
ResultsText read_results_text(std::string_view text, std::string_view fingerprint, const std::string& name);

/// The bytes of the results file `path`, read only. Throws ConfigError, naming it, if it is not
/// a file pcsim made (a symbolic link, a file of several hard links, not a regular file);
/// Error if it cannot be read.
std::string read_results_file(const std::string& path);

class ResultsFile {
 public:
  /// Opens (or makes) `path`, locks it, reads it and checks it whole (read_results_text), then
  /// drops a partial last line pcsim wrote, and knows the runs it holds. Throws ConfigError,
  /// the file untouched, if another process holds it, if it is not a file pcsim made, or if a
  /// line is not a result of this sweep (naming the file and line); Error if it cannot be opened.
  ResultsFile(const std::string& path, const std::string& fingerprint);
  ~ResultsFile();
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;

  const std::set<std::string>& done() const noexcept { return done_; }
  /// Appends `line` (one JSON object, without its newline). Not thread-safe: callers serialise.
  void append(const std::string& line);

 private:
  std::string path_;
  int fd_ = -1;
  std::set<std::string> done_;
};

}  // namespace pagecache::sweep
