#pragma once
// The results files of a sweep's folder (OUT/results-I-of-N.jsonl), of whatever shard splits
// ran into it, read together: a run recorded in any of them is done, whichever split runs
// next, and merge takes them all.

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::sweep {

/// The paths of the results files in `dir`, sorted.
std::vector<std::string> results_files(const std::string& dir);

/// Calls `each` with every whole line of every results file in `dir` (read_results_file, then
/// read_results_text: each checked as a result of the sweep whose base has `fingerprint`), in
/// file and line order: its run's id, the line, the file's name and the line's number. A last
/// line cut short (a shard killed, or still writing it) is left out. Throws ConfigError, naming
/// the file (and line), at the first file or line that is not pcsim's.
void for_each_result(const std::string& dir, std::string_view fingerprint,
                     const std::function<void(const std::string& id, std::string_view line, const std::string& file, std::size_t number)>& each);

}  // namespace pagecache::sweep
