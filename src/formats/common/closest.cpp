#include "formats/common/closest.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace pagecache::formats {

namespace {

// Edit distance with transpositions (optimal string alignment): "file_sise" is 1 from
// "file_size", "file_szie" 1 too.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  std::iota(d[0].begin(), d[0].end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::string closest(std::string_view typed, const std::set<std::string>& candidates) {
  // Keys are short: more than two edits, or a third of the word, is another word.
  if (typed.size() > 64) return {};
  std::string best;
  std::size_t best_distance = 3;
  for (const std::string& c : candidates) {
    if (c.size() > 64) continue;
    const std::size_t d = edit_distance(typed, c);
    if (d < best_distance && 3 * d <= std::max(typed.size(), c.size())) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

}  // namespace pagecache::formats
