#include "chart/gantt_chart.hpp"

#include "chart/html_text.hpp"
#include "chart/text_width.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::chart {

namespace {

constexpr double kRowHeight = 16.0;
// The left margin grows to the widest label up to this share of the width; longer labels are
// shortened to it (the full one is a tooltip), so the plot keeps most of the width.
constexpr double kMaxLabelShare = 0.4;
// Between the SVG's left edge and a label, and between a label and the plot.
constexpr double kEdgeGap = 4.0;
constexpr double kPlotGap = 6.0;

}  // namespace

std::string gantt_chart(const Gantt& c) {
  Plot p = c.plot;
  double widest = 0.0;
  for (const GanttRow& row : c.rows) widest = std::max(widest, text_width(row.label));
  p.left = std::max({p.left, 160.0, std::min(kEdgeGap + widest + kPlotGap, p.width * kMaxLabelShare)});
  const double room = p.left - kPlotGap - kEdgeGap;
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
                       fixed(p.left - kPlotGap, 1), fixed(y + kRowHeight / 2, 1), escape(row.label), escape(fit_text(row.label, room)));
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
