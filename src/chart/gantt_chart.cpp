#include "chart/gantt_chart.hpp"

#include "chart/html_text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::chart {

namespace {

constexpr double kRowHeight = 16.0;
// Row labels longer than this are cut to fit the left margin (the full one is a tooltip).
constexpr std::size_t kLabelChars = 22;

}  // namespace

std::string gantt_chart(const Gantt& c) {
  Plot p = c.plot;
  p.left = std::max(p.left, 160.0);
  p.height = p.top + p.bottom + kRowHeight * static_cast<double>(std::max<std::size_t>(c.rows.size(), 1));
  p.x = {0.0, c.x_end > 0 ? c.x_end : 1.0, c.x_title};
  p.y = {0.0, static_cast<double>(std::max<std::size_t>(c.rows.size(), 1)), ""};

  std::string out = svg_open(c.kind, c.series.size(), c.rows.size(), p, c.title);
  draw_axes(out, p, true, false);
  for (std::size_t r = 0; r < c.rows.size(); ++r) {
    const GanttRow& row = c.rows[r];
    const double y = p.top + kRowHeight * static_cast<double>(r);
    out += fmt::format("<g class=\"gantt-row\"><text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\" dominant-baseline=\"middle\">"
                       "<title>{}</title>{}</text>",
                       fixed(p.left - 6, 1), fixed(y + kRowHeight / 2, 1), escape(row.label), escape(shorten(row.label, kLabelChars)));
    for (const GanttBar& b : row.bars) {
      const GanttSeries& s = c.series[b.series];
      // At least a hairline: a phase of a millisecond in an hour-long run stays visible.
      const double width = std::max(p.px(b.end) - p.px(b.start), 0.5);
      out += fmt::format("<rect data-series=\"{}\" fill=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>", escape(s.name), s.colour,
                         fixed(p.px(b.start), 1), fixed(y + 2, 1), fixed(width, 1), fixed(kRowHeight - 4, 1));
    }
    out += "</g>\n";
  }
  std::vector<LegendEntry> legend;
  for (const GanttSeries& s : c.series) legend.push_back({s.name, s.colour, 1.0});
  draw_legend(out, p, legend);
  return out + "</svg>\n";
}

}  // namespace pagecache::chart
