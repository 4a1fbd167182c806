#include "report/html_report.hpp"

#include "chart/html_text.hpp"
#include "chart/page.hpp"
#include "report/figures.hpp"

#include <pagecache/version.hpp>

#include <fmt/format.h>

namespace pagecache::report {

namespace {

using chart::fixed;

std::string gb(std::int64_t bytes) { return fixed(static_cast<double>(bytes) / 1e9, 3) + " GB"; }

std::string summary_table(const RunResult& r, const ReportActivity& a) {
  const RunSummary& s = r.summary;
  auto totals = [](const PhaseTotals& t) { return fmt::format("{} s, {}", fixed(t.seconds, 3), gb(t.bytes)); };
  std::vector<std::vector<std::string>> rows = {
      {"makespan (last task ended)", fixed(s.makespan, 3) + " s"},
      {"end time (last event, dirty data written back)", fixed(s.end_time, 3) + " s"},
      {"read phases (time summed over tasks, bytes)", totals(s.read)},
      {"compute phases", totals(s.compute)},
      {"write phases", totals(s.write)},
      {"read from disk", gb(s.disk_read_bytes)},
      {"read from the page cache", gb(s.cache_read_bytes)},
      {"written back, forced (writers: dirty limit, reclaim)", gb(s.forced_flush_bytes)},
      {"written back, periodic (the flusher)", gb(s.periodic_flush_bytes)},
      {"evicted", gb(s.evicted_bytes)},
      {"peak dirty", gb(s.peak_dirty_bytes)},
      {"events simulated", fmt::format("{}", s.events)},
  };
  if (a.recorded()) {
    std::array<std::int64_t, ReportActivity::kCauses> by_cause{};
    for (const auto& bucket : a.buckets())
      for (std::size_t c = 0; c < by_cause.size(); ++c) by_cause[c] += bucket.flushed[c];
    for (std::size_t c = 0; c < by_cause.size(); ++c) {
      rows.push_back({"written back: " + std::string(to_string(static_cast<FlushCause>(c))), gb(by_cause[c])});
    }
  }
  return "<h2>Summary</h2>\n" + chart::html_table({"", "value"}, rows);
}

}  // namespace

std::string report_html(const Scenario& scenario, const RunResult& result, const ReportActivity& activity) {
  const std::string name = scenario.title.empty() ? scenario.source : scenario.title;
  std::string body = fmt::format("<h1>pcsim report: {}</h1>\n", chart::escape(name));
  body += fmt::format("<p class=\"note\">Scenario {} (profile {}), simulated by pcsim {}. The figures are in the files beside this "
                      "page (timeline.csv, memory.csv, cache.csv, summary.json).</p>\n",
                      chart::escape(scenario.source), to_string(scenario.profile), kVersion);
  body += summary_table(result, activity);
  body += memory_figures(result);
  body += phase_figure(result);
  body += cache_figure(result);
  body += activity_figure(activity);
  body += fmt::format("<footer>pcsim {}, scenario {}</footer>\n", kVersion, chart::escape(scenario.source));
  return chart::html_page("pcsim report: " + name, body);
}

}  // namespace pagecache::report
