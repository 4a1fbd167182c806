#include "chart/bar_chart.hpp"

#include "chart/html_text.hpp"
#include "chart/text_width.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::chart {

namespace {

// Category labels are rotated by this much (degrees, anticlockwise) so that long ones fit.
constexpr double kAngle = 35.0;
// A label's ascent and descent (pixels): how far its box reaches across its baseline.
constexpr double kAscent = 0.93 * kFontPx;
constexpr double kDescent = 0.24 * kFontPx;
// Room kept for the x axis' title under the labels, and clear of the SVG's left edge.
constexpr double kTitleRoom = 22.0;
constexpr double kEdgeGap = 2.0;
// Between neighbouring rotated labels, across their baselines.
constexpr double kLabelGap = 3.0;
// The bottom margin grows to the longest label up to this (the chart grows with it).
constexpr double kMaxBottom = 180.0;

double radians(double degrees) { return degrees * std::acos(-1.0) / 180.0; }

// From the base line down to a label's anchor: 12 px, lower if the first label's top edge, rising
// to its anchor, would reach the y axis' lowest tick label (centred on the base line, its right
// end 6 px left of the axis): in a narrow first column it starts close to that label.
double anchor_drop(double slot) {
  const double cos_a = std::cos(radians(kAngle)), sin_a = std::sin(radians(kAngle));
  const double clear = line_height() / 2 + kLabelGap + kAscent * cos_a - (slot / 2 + 6 - kAscent * sin_a) * sin_a / cos_a;
  return std::max(12.0, clear);
}

// The bottom margin that holds the longest label whole and the axis title under it.
double bottom_for(const std::vector<std::string>& categories, double slot) {
  double widest = 0.0;
  for (const std::string& c : categories) widest = std::max(widest, text_width(c));
  return anchor_drop(slot) + widest * std::sin(radians(kAngle)) + kDescent * std::cos(radians(kAngle)) + kTitleRoom;
}

// The category labels, rotated, anchored at their end under each category: every k-th when
// neighbours would overlap, each shortened to what fits between its anchor and the SVG's left
// edge and above the axis title, its full name in a tooltip. A category left unlabelled gets
// its tooltip on a transparent column over its bars.
void draw_categories(std::string& out, const Plot& p, const std::vector<std::string>& categories, double slot) {
  const double cos_a = std::cos(radians(kAngle)), sin_a = std::sin(radians(kAngle));
  const double base_y = p.py(p.y.lo), anchor_y = base_y + anchor_drop(slot);
  const std::size_t every = static_cast<std::size_t>(std::max(1.0, std::ceil((line_height() + kLabelGap) / (slot * sin_a))));
  const double below = (p.height - kTitleRoom - anchor_y - kDescent * cos_a) / sin_a;
  out += "<g class=\"categories\">";
  for (std::size_t i = 0; i < categories.size(); ++i) {
    const double x = p.px(static_cast<double>(i)) + slot / 2;
    if (i % every != 0) {
      out += fmt::format("<rect class=\"category\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fff\" fill-opacity=\"0\"><title>{}</title></rect>",
                         fixed(x - slot / 2, 1), fixed(p.top, 1), fixed(slot, 1), fixed(base_y - p.top, 1), escape(categories[i]));
      continue;
    }
    const double room = std::min(below, (x - kAscent * sin_a - kEdgeGap) / cos_a);
    out += fmt::format("<text class=\"tick\" transform=\"translate({} {}) rotate(-{})\" text-anchor=\"end\"><title>{}</title>{}</text>",
                       fixed(x, 1), fixed(anchor_y, 1), fixed(kAngle, 0), escape(categories[i]), escape(fit_text(categories[i], room)));
  }
  out += "</g>\n";
}

}  // namespace

std::string bar_chart(const BarChart& c) {
  const std::size_t n = c.categories.size();
  double highest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (const BarSeries& s : c.series) {
      sum += s.values[i];
      highest = std::max(highest, s.values[i]);
    }
    if (c.stacked) highest = std::max(highest, sum);
  }
  Plot p = c.plot;
  // Long labels get room under the bars, the plot keeping its height.
  const double slot = p.plot_width() / static_cast<double>(std::max<std::size_t>(n, 1));
  p.bottom = std::max(c.plot.bottom, std::min(bottom_for(c.categories, slot), kMaxBottom));
  p.height += p.bottom - c.plot.bottom;
  p.x = {0.0, static_cast<double>(std::max<std::size_t>(n, 1)), c.x_title};
  p.y = nice_range(0.0, highest > 0 ? highest : 1.0, c.y_title, 5);

  std::string out = svg_open(c.kind, c.series.size(), n, p, c.title);
  draw_axes(out, p, false);
  const double bar = c.stacked ? slot * 0.7 : slot * 0.8 / static_cast<double>(std::max<std::size_t>(c.series.size(), 1));
  std::vector<double> below(n, 0.0);
  std::vector<LegendEntry> legend;
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    const BarSeries& s = c.series[k];
    legend.push_back({s.name, s.colour, 1.0});
    out += fmt::format("<g class=\"series\" data-series=\"{}\" fill=\"{}\">", escape(s.name), s.colour);
    for (std::size_t i = 0; i < n; ++i) {
      const double x = c.stacked ? p.px(static_cast<double>(i)) + (slot - bar) / 2 : p.px(static_cast<double>(i)) + slot * 0.1 + bar * static_cast<double>(k);
      const double y0 = c.stacked ? below[i] : 0.0;
      const double y1 = y0 + s.values[i];
      if (c.stacked) below[i] = y1;
      out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>", fixed(x, 1), fixed(p.py(y1), 1), fixed(bar, 1),
                         fixed(p.py(y0) - p.py(y1), 1));
    }
    out += "</g>\n";
  }
  draw_categories(out, p, c.categories, slot);
  draw_legend(out, p, legend);
  return out + "</svg>\n";
}

}  // namespace pagecache::chart
