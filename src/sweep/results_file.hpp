#pragma once
// A shard's results: one JSON line per finished run, appended. Each line goes to the file in
// one write() on a descriptor opened O_APPEND, so that a shard killed at any moment leaves
// whole lines and at most a partial last one; opening the file again cuts such a tail off. The
// file is locked (flock) while a shard writes it: a second process on the same shard is
// refused instead of interleaving.

#include <set>
#include <string>

namespace pagecache::sweep {

class ResultsFile {
 public:
  /// Opens (or makes) `path`, locks it, drops a partial last line, and reads the ids of the
  /// runs it holds. Throws ConfigError if another process holds it, or a line is not a result
  /// pcsim wrote (naming the file and line); Error if it cannot be opened.
  explicit ResultsFile(const std::string& path);
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

/// The id of a result line (its "id" member), or empty if the line is not a result.
std::string result_id(const std::string& line);

}  // namespace pagecache::sweep
