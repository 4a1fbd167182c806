#include "chart/bar_chart.hpp"

#include "chart/html_text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::chart {

namespace {

// Category labels longer than this are cut; the rotated labels must fit in the bottom margin.
constexpr std::size_t kLabelChars = 18;

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
  p.x = {0.0, static_cast<double>(std::max<std::size_t>(n, 1)), c.x_title};
  p.y = nice_range(0.0, highest > 0 ? highest : 1.0, c.y_title, 5);

  std::string out = svg_open(c.kind, c.series.size(), n, p, c.title);
  draw_axes(out, p, false);
  const double slot = p.plot_width() / static_cast<double>(std::max<std::size_t>(n, 1));
  const double bar = c.stacked ? slot * 0.7 : slot * 0.8 / static_cast<double>(std::max<std::size_t>(c.series.size(), 1));
  const double base_y = p.py(0.0);
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
  // Category labels, rotated so that long ones do not overlap; a tooltip holds each in full.
  out += "<g class=\"categories\">";
  for (std::size_t i = 0; i < n; ++i) {
    const double x = p.px(static_cast<double>(i)) + slot / 2;
    out += fmt::format("<text class=\"tick\" transform=\"translate({} {}) rotate(-35)\" text-anchor=\"end\"><title>{}</title>{}</text>",
                       fixed(x, 1), fixed(base_y + 12, 1), escape(c.categories[i]), escape(shorten(c.categories[i], kLabelChars)));
  }
  out += "</g>\n";
  draw_legend(out, p, legend);
  return out + "</svg>\n";
}

}  // namespace pagecache::chart
