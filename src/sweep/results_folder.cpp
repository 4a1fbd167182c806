#include "sweep/results_folder.hpp"

#include "sweep/results_file.hpp"

#include <algorithm>
#include <filesystem>
#include <regex>

namespace pagecache::sweep {

namespace fs = std::filesystem;

std::vector<std::string> results_files(const std::string& dir) {
  static const std::regex shard_file(R"(results-[0-9]+-of-[0-9]+\.jsonl)");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (std::regex_match(entry.path().filename().string(), shard_file)) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void for_each_result(const std::string& dir, std::string_view fingerprint,
                     const std::function<void(const std::string& id, std::string_view line, const std::string& file, std::size_t number)>& each) {
  for (const std::string& path : results_files(dir)) {
    const std::string text = read_results_file(path);
    const ResultsText results = read_results_text(text, fingerprint, path);
    const std::string name = fs::path(path).filename().string();
    for (const ResultsText::Line& line : results.lines) each(line.id, line.text, name, line.number);
  }
}

}  // namespace pagecache::sweep
