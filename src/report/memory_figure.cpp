#include "report/figures.hpp"

#include "chart/area_chart.hpp"
#include "chart/html_text.hpp"
#include "chart/palette.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace pagecache::report {

namespace {

using chart::escape;

// The rows to draw: all if few, else per time bucket the last row, which is the step
// function's value at the end of that bucket (changes inside a bucket collapse into it).
std::vector<const MemoryRow*> downsample(const std::vector<const MemoryRow*>& rows, double end) {
  if (rows.size() <= kMaxMemoryPoints || !(end > 0.0)) return rows;
  std::vector<const MemoryRow*> out;
  std::size_t last_bucket = SIZE_MAX;
  for (const MemoryRow* row : rows) {
    const double f = std::clamp(row->time / end, 0.0, 1.0);
    const std::size_t bucket = std::min(static_cast<std::size_t>(f * static_cast<double>(kMaxMemoryPoints)), kMaxMemoryPoints - 1);
    if (bucket == last_bucket) out.back() = row;
    else out.push_back(row);
    last_bucket = bucket;
  }
  return out;
}

std::string host_chart(const std::string& host, const std::vector<const MemoryRow*>& rows, double end) {
  chart::AreaChart c;
  c.kind = "memory";
  c.title = "memory of host " + host;
  c.x_title = "time (s)";
  c.y_title = "memory (GB)";
  c.x_end = end;
  c.series = {{"anonymous", chart::kReddishPurple, {}},
              {"cached clean", chart::kSkyBlue, {}},
              {"dirty", chart::kVermillion, {}},
              {"writeback", chart::kOrange, {}},
              {"free", chart::kBlack, {}, true, 0.08}};
  for (const MemoryRow* row : rows) {
    const MemoryState& s = row->state;
    c.x.push_back(row->time);
    // Pages of copies in flight count as cached (as in memory.csv): the stack adds up to total.
    const double values[] = {static_cast<double>(s.anonymous), static_cast<double>(s.cached + s.reserved - s.dirty - s.writeback),
                             static_cast<double>(s.dirty), static_cast<double>(s.writeback), static_cast<double>(s.free)};
    for (std::size_t k = 0; k < 5; ++k) c.series[k].y.push_back(values[k] / 1e9);
  }
  return chart::area_chart(c);
}

}  // namespace

std::string memory_figures(const RunResult& r) {
  std::string out = "<h2>Memory</h2>\n";
  if (r.memory.empty()) return out + "<p class=\"note\">No memory rows were recorded.</p>\n";
  // Hosts in the order of their first row; each host's rows in time order.
  std::vector<std::string> hosts;
  std::unordered_map<std::string, std::size_t> index;
  std::vector<std::vector<const MemoryRow*>> rows;
  double end = r.summary.end_time;
  for (const MemoryRow& m : r.memory) {
    end = std::max(end, m.time);
    auto [it, inserted] = index.try_emplace(r.host_name(m), hosts.size());
    if (inserted) {
      hosts.push_back(r.host_name(m));
      rows.emplace_back();
    }
    if (it->second < kMaxMemoryHosts) rows[it->second].push_back(&m);
  }
  if (hosts.size() > kMaxMemoryHosts) {
    out += fmt::format("<p class=\"note\">{} hosts: the first {} are drawn (memory.csv has them all).</p>\n", hosts.size(), kMaxMemoryHosts);
  }
  for (std::size_t h = 0; h < hosts.size() && h < kMaxMemoryHosts; ++h) {
    const std::vector<const MemoryRow*> drawn = downsample(rows[h], end);
    out += fmt::format("<h3>Host {}</h3>\n", escape(hosts[h]));
    if (drawn.size() < rows[h].size()) {
      out += fmt::format("<p class=\"note\">Downsampled from {} rows to {} (the last row in each of {} time buckets).</p>\n", rows[h].size(),
                         drawn.size(), kMaxMemoryPoints);
    }
    out += host_chart(hosts[h], drawn, end);
  }
  return out;
}

}  // namespace pagecache::report
