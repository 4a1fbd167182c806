#include "report/figures.hpp"

#include "chart/bar_chart.hpp"
#include "chart/html_text.hpp"
#include "chart/palette.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

namespace pagecache::report {

std::string cache_figure(const RunResult& r) {
  std::string out = "<h2>Page cache contents after each I/O phase</h2>\n";
  if (!r.cache_not_recorded.empty()) {
    return out + fmt::format("<p class=\"note\">Not recorded: {}.</p>\n", chart::escape(r.cache_not_recorded));
  }
  if (r.cache.empty() || r.files.empty()) return out + "<p class=\"note\">No I/O phase, no file: nothing was cached.</p>\n";
  // The rows of one I/O phase are consecutive, a file each, in `files` order.
  std::vector<std::uint32_t> phases;
  std::vector<std::vector<std::int64_t>> cached;  // [phase][file]
  std::size_t all_phases = 0;
  for (std::size_t i = 0; i < r.cache.size(); ++i) {
    const CacheRow& row = r.cache[i];
    if (i == 0 || r.cache[i - 1].phase != row.phase) {
      if (++all_phases <= kMaxCachePhases) {
        phases.push_back(row.phase);
        cached.emplace_back(r.files.size(), 0);
      }
    }
    if (all_phases <= kMaxCachePhases) cached.back()[row.file] += row.cached;
  }
  // The largest files (most bytes over the phases shown) apart, in the scenario's order.
  std::vector<std::int64_t> total(r.files.size(), 0);
  for (const auto& per_file : cached)
    for (std::size_t f = 0; f < per_file.size(); ++f) total[f] += per_file[f];
  std::vector<std::size_t> files(r.files.size());
  std::iota(files.begin(), files.end(), 0);
  const bool grouped = files.size() > kMaxCacheFiles + 1;
  if (grouped) {
    std::stable_sort(files.begin(), files.end(), [&](std::size_t a, std::size_t b) { return total[a] > total[b]; });
    files.resize(kMaxCacheFiles);
    std::sort(files.begin(), files.end());
  }
  chart::BarChart c;
  c.kind = "cache";
  c.title = "page cache contents per file after each I/O phase";
  c.x_title = "after the I/O phase";
  c.y_title = "cached (GB)";
  c.plot.bottom = 100;
  for (const std::uint32_t p : phases) {
    const PhaseRow& row = r.timeline.at(p);
    c.categories.push_back(fmt::format("{}/{} {}", r.app_name(row), r.task_name(row), to_string(row.phase)));
  }
  std::vector<bool> apart(r.files.size(), false);
  for (std::size_t k = 0; k < files.size(); ++k) {
    apart[files[k]] = true;
    chart::BarSeries s{r.files[files[k]], chart::kPalette[k % chart::kPalette.size()], {}};
    for (const auto& per_file : cached) s.values.push_back(static_cast<double>(per_file[files[k]]) / 1e9);
    c.series.push_back(std::move(s));
  }
  if (grouped) {
    chart::BarSeries other{fmt::format("{} other files", r.files.size() - files.size()), chart::kPalette[kMaxCacheFiles], {}};
    for (const auto& per_file : cached) {
      std::int64_t sum = 0;
      for (std::size_t f = 0; f < per_file.size(); ++f)
        if (!apart[f]) sum += per_file[f];
      other.values.push_back(static_cast<double>(sum) / 1e9);
    }
    c.series.push_back(std::move(other));
    out += fmt::format("<p class=\"note\">{} files: the {} that were cached most are drawn apart, the others together.</p>\n",
                       r.files.size(), kMaxCacheFiles);
  }
  if (all_phases > phases.size()) {
    out += fmt::format("<p class=\"note\">{} I/O phases: the first {} are drawn (cache.csv has them all).</p>\n", all_phases, phases.size());
  }
  return out + chart::bar_chart(c);
}

}  // namespace pagecache::report
