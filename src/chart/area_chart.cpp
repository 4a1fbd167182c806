#include "chart/area_chart.hpp"

#include "chart/html_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::chart {

namespace {

// A step outline as path commands, left to right from x[0] to x_end at heights `level`: "H" and
// "V" only, a "V" only where the height (in whole tenths of a pixel) changes.
void forward_steps(std::string& d, const Plot& p, const std::vector<double>& x, double x_end, const std::vector<double>& level) {
  std::string current = fixed(p.py(level[0]), 1);
  for (std::size_t i = 1; i < x.size(); ++i) {
    std::string next = fixed(p.py(level[i]), 1);
    if (next == current) continue;
    d += fmt::format("H{}V{}", fixed(p.px(x[i]), 1), next);
    current = std::move(next);
  }
  d += fmt::format("H{}", fixed(p.px(x_end), 1));
}

// The same outline right to left, from x_end back to x[0].
void backward_steps(std::string& d, const Plot& p, const std::vector<double>& x, const std::vector<double>& level) {
  std::string current = fixed(p.py(level.back()), 1);
  d += fmt::format("V{}", current);
  for (std::size_t i = x.size() - 1; i > 0; --i) {
    std::string next = fixed(p.py(level[i - 1]), 1);
    if (next == current) continue;
    d += fmt::format("H{}V{}", fixed(p.px(x[i]), 1), next);
    current = std::move(next);
  }
  d += fmt::format("H{}", fixed(p.px(x[0]), 1));
}

}  // namespace

std::string area_chart(const AreaChart& c) {
  const std::size_t n = c.x.size();
  // The stack's top after each stacked series, and the highest value anywhere.
  std::vector<std::vector<double>> tops;
  std::vector<double> running(n, 0.0);
  double highest = 0.0;
  for (const AreaSeries& s : c.series) {
    if (s.stacked) {
      for (std::size_t i = 0; i < n; ++i) running[i] += s.y[i];
      tops.push_back(running);
      for (const double v : running) highest = std::max(highest, v);
    } else {
      tops.push_back(s.y);
      for (const double v : s.y) highest = std::max(highest, v);
    }
  }
  Plot p = c.plot;
  const double x_lo = n > 0 ? std::min(c.x.front(), 0.0) : 0.0;
  p.x = {x_lo, c.x_end > x_lo ? c.x_end : x_lo + 1.0, c.x_title};
  p.y = nice_range(0.0, highest > 0 ? highest : 1.0, c.y_title, 5);

  std::string out = svg_open(c.kind, c.series.size(), n, p, c.title);
  draw_axes(out, p);
  std::vector<LegendEntry> legend;
  std::vector<double> below(n, 0.0);
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    const AreaSeries& s = c.series[k];
    legend.push_back({s.name, s.colour, s.opacity});
    std::string d;
    if (n > 0) {
      const std::vector<double>& top = tops[k];
      d = fmt::format("M{} {}", fixed(p.px(c.x[0]), 1), fixed(p.py(top[0]), 1));
      forward_steps(d, p, c.x, c.x_end, top);
      if (s.stacked) {
        backward_steps(d, p, c.x, below);
        d += "Z";
        below = top;
      }
    }
    if (s.stacked) {
      out += fmt::format("<path class=\"series\" data-series=\"{}\" fill=\"{}\" fill-opacity=\"{}\" d=\"{}\"/>\n", escape(s.name), s.colour,
                         fixed(s.opacity, 2), d);
    } else {
      out += fmt::format("<path class=\"series line\" data-series=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" d=\"{}\"/>\n",
                         escape(s.name), s.colour, d);
    }
  }
  draw_legend(out, p, legend);
  return out + "</svg>\n";
}

}  // namespace pagecache::chart
