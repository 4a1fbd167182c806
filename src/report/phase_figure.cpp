#include "report/figures.hpp"

#include "chart/area_chart.hpp"
#include "chart/gantt_chart.hpp"
#include "chart/palette.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string_view>
#include <utility>

namespace pagecache::report {

namespace {

constexpr std::array<std::string_view, 3> kKinds = {"read", "compute", "write"};
constexpr std::array<std::string_view, 3> kColours = {chart::kBlue, chart::kBluishGreen, chart::kVermillion};

std::size_t kind_of(PhaseKind phase) {
  return static_cast<std::size_t>(std::find(kKinds.begin(), kKinds.end(), to_string(phase)) - kKinds.begin());
}

// The run's end (dirty data written back), as the memory and activity charts end, so that the
// charts' time axes line up.
double end_of(const RunResult& r) {
  double end = r.summary.end_time;
  for (const PhaseRow& p : r.timeline) end = std::max(end, p.end);
  return end;
}

std::string gantt(const RunResult& r, const std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t>& tasks) {
  chart::Gantt g;
  g.title = "phases of each task";
  g.x_title = "time (s)";
  g.x_end = end_of(r);
  for (std::size_t k = 0; k < kKinds.size(); ++k) g.series.push_back({std::string(kKinds[k]), kColours[k]});
  std::vector<chart::GanttRow> rows(tasks.size());
  std::vector<double> first_start(tasks.size(), INFINITY);
  for (const PhaseRow& p : r.timeline) {
    const std::size_t t = tasks.at({p.app, p.task});
    const std::size_t kind = kind_of(p.phase);
    if (kind >= kKinds.size()) continue;
    rows[t].label = r.app_name(p) + "/" + r.task_name(p);
    rows[t].bars.push_back({p.start, p.end, static_cast<std::uint8_t>(kind)});
    first_start[t] = std::min(first_start[t], p.start);
  }
  // Rows by when the task started, ties in the order the tasks first appear (stable).
  std::vector<std::size_t> order(rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return first_start[a] < first_start[b]; });
  for (const std::size_t i : order) g.rows.push_back(std::move(rows[i]));
  return chart::gantt_chart(g);
}

// The mean number of phases of one kind in progress in each bucket: a sweep over their starts
// (+1) and ends (-1) in time order, each constant stretch added to the buckets it overlaps.
std::vector<double> mean_in_progress(std::vector<std::pair<double, int>> events, double width, std::size_t buckets) {
  std::sort(events.begin(), events.end());
  std::vector<double> area(buckets, 0.0);
  auto add = [&](double lo, double hi, int count) {
    if (count == 0 || !(hi > lo)) return;
    const auto bucket = [&](double t) { return std::min(static_cast<std::size_t>(std::max(t, 0.0) / width), buckets - 1); };
    for (std::size_t b = bucket(lo); b <= bucket(hi); ++b) {
      const double overlap = std::min(hi, static_cast<double>(b + 1) * width) - std::max(lo, static_cast<double>(b) * width);
      if (overlap > 0) area[b] += overlap * count;
    }
  };
  double t = 0.0;
  int count = 0;
  for (const auto& [time, delta] : events) {
    add(t, time, count);
    t = time;
    count += delta;
  }
  for (double& a : area) a /= width;
  return area;
}

std::string aggregate(const RunResult& r, std::size_t tasks) {
  const double end = end_of(r) > 0 ? end_of(r) : 1.0;
  const std::size_t buckets = kPhaseBuckets;
  const double width = end / static_cast<double>(buckets);
  std::array<std::vector<std::pair<double, int>>, 3> events;
  for (const PhaseRow& p : r.timeline) {
    const std::size_t kind = kind_of(p.phase);
    if (kind >= kKinds.size()) continue;
    events[kind].push_back({p.start, 1});
    events[kind].push_back({p.end, -1});
  }
  chart::AreaChart c;
  c.kind = "phases";
  c.title = "tasks in each phase over time";
  c.x_title = "time (s)";
  c.y_title = "tasks (mean over each bucket)";
  c.x_end = end;
  for (std::size_t b = 0; b < buckets; ++b) c.x.push_back(static_cast<double>(b) * width);
  for (std::size_t k = 0; k < kKinds.size(); ++k) {
    c.series.push_back({std::string(kKinds[k]), kColours[k], mean_in_progress(std::move(events[k]), width, buckets)});
  }
  return fmt::format("<p class=\"note\">{} tasks, more than the {} a Gantt chart shows: the number of tasks reading, computing and writing "
                     "over time instead, in {} buckets of {:.6g} s (timeline.csv has every phase).</p>\n",
                     tasks, kMaxGanttTasks, buckets, width) +
         chart::area_chart(c);
}

}  // namespace

std::string phase_figure(const RunResult& r) {
  std::string out = "<h2>Phases</h2>\n";
  if (r.timeline.empty()) return out + "<p class=\"note\">No task ran.</p>\n";
  // The tasks, numbered in the order they first appear; counting stops past the Gantt's limit.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> tasks;
  for (const PhaseRow& p : r.timeline) {
    tasks.try_emplace({p.app, p.task}, tasks.size());
    if (tasks.size() > kMaxGanttTasks) break;
  }
  if (tasks.size() <= kMaxGanttTasks) return out + gantt(r, tasks);
  std::set<std::pair<std::uint32_t, std::uint32_t>> all;
  for (const PhaseRow& p : r.timeline) all.insert({p.app, p.task});
  return out + aggregate(r, all.size());
}

}  // namespace pagecache::report
