#include "chart/frame.hpp"

#include "chart/html_text.hpp"
#include "chart/text_width.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::chart {

namespace {

double tick_step(double lo, double hi, int target) {
  const double raw = (hi - lo) / std::max(target, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * magnitude >= raw) return m * magnitude;
  }
  return 10.0 * magnitude;
}

// Space between neighbouring tick labels, in pixels: touching labels read as one number.
constexpr double kTickGap = 8.0;

bool in_range(double v, const Axis& a, double step) { return v >= a.lo - 1e-9 * step && v <= a.hi + 1e-9 * step; }

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> out;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double step = tick_step(lo, hi, target);
  const double first = std::floor(lo / step + 1e-9) * step;
  for (int i = 0;; ++i) {
    const double v = first + i * step;
    out.push_back(v);
    if (v >= hi - step * 1e-9) break;
  }
  return out;
}

Axis nice_range(double lo, double hi, std::string title, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {std::isfinite(lo) ? lo : 0.0, (std::isfinite(lo) ? lo : 0.0) + 1.0, std::move(title)};
  const std::vector<double> ticks = nice_ticks(lo, hi, target);
  return {ticks.front(), ticks.back(), std::move(title)};
}

std::string tick_label(double value, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return fixed(value, std::clamp(decimals, 0, 6));
}

std::vector<double> axis_ticks(const Axis& axis, double pixels, bool horizontal, int target) {
  std::vector<double> kept;
  for (int t = std::max(target, 1); t >= 1; --t) {
    const std::vector<double> ticks = nice_ticks(axis.lo, axis.hi, t);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
    kept.clear();
    for (const double v : ticks)
      if (in_range(v, axis, step)) kept.push_back(v);
    const double apart = pixels * step / (axis.hi - axis.lo);  // between neighbouring ticks
    bool fits = true;
    for (std::size_t i = 1; i < kept.size() && fits; ++i) {
      const double need = horizontal ? (text_width(tick_label(kept[i - 1], step)) + text_width(tick_label(kept[i], step))) / 2 : line_height();
      fits = need + kTickGap <= apart;
    }
    if (fits) break;
  }
  return kept;
}

std::string svg_open(std::string_view kind, std::size_t series, std::size_t rows, const Plot& plot, std::string_view title) {
  return fmt::format(
      "<svg class=\"chart\" data-chart=\"{}\" data-series=\"{}\" data-rows=\"{}\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "role=\"img\"><title>{}</title>\n",
      escape(kind), series, rows, fixed(plot.width, 0), fixed(plot.height, 0), fixed(plot.width, 0), fixed(plot.height, 0),
      escape(title));
}

void draw_axes(std::string& out, const Plot& p, bool x_ticks, bool y_ticks) {
  const double x0 = p.left, x1 = p.left + p.plot_width(), y0 = p.top + p.plot_height(), y1 = p.top;
  out += "<g class=\"axes\">\n";
  const std::vector<double> yt = y_ticks ? axis_ticks(p.y, p.plot_height(), false, 5) : std::vector<double>{};
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (const double v : yt) {
    const std::string y = fixed(p.py(v), 1);
    out += fmt::format("<line class=\"grid\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/><text class=\"tick\" x=\"{}\" y=\"{}\" "
                       "text-anchor=\"end\" dominant-baseline=\"middle\">{}</text>\n",
                       fixed(x0, 1), y, fixed(x1, 1), y, fixed(x0 - 6, 1), y, tick_label(v, ystep));
  }
  if (x_ticks) {
    const std::vector<double> xt = axis_ticks(p.x, p.plot_width(), true, 8);
    const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
    for (const double v : xt) {
      const std::string x = fixed(p.px(v), 1);
      out += fmt::format("<line class=\"tick-mark\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/><text class=\"tick\" x=\"{}\" y=\"{}\" "
                         "text-anchor=\"middle\">{}</text>\n",
                         x, fixed(y0, 1), x, fixed(y0 + 5, 1), x, fixed(y0 + 17, 1), tick_label(v, xstep));
    }
  }
  out += fmt::format("<path class=\"frame\" d=\"M{} {}V{}H{}\"/>\n", fixed(x0, 1), fixed(y1, 1), fixed(y0, 1), fixed(x1, 1));
  if (!p.x.title.empty()) out += fmt::format("<text class=\"axis-title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", fixed(x0 + p.plot_width() / 2, 1),
                     fixed(p.height - 6, 1), escape(p.x.title));
  if (!p.y.title.empty()) out += fmt::format("<text class=\"axis-title\" transform=\"translate({} {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     fixed(16, 1), fixed(y1 + p.plot_height() / 2, 1), escape(p.y.title));
  out += "</g>\n";
}

void draw_legend(std::string& out, const Plot& p, const std::vector<LegendEntry>& entries) {
  const double x = p.left + p.plot_width() + 16;
  const double room = p.width - (x + 18) - 4;
  out += "<g class=\"legend\">\n";
  std::vector<const LegendEntry*> drawn;
  for (const LegendEntry& e : entries) {
    const auto same = [&](const LegendEntry* d) { return d->name == e.name && d->colour == e.colour && d->opacity == e.opacity; };
    if (std::any_of(drawn.begin(), drawn.end(), same)) continue;
    const double y = p.top + 4 + 18.0 * static_cast<double>(drawn.size());
    drawn.push_back(&e);
    out += fmt::format(
        "<g class=\"legend-item\" data-series=\"{}\"><title>{}</title><rect x=\"{}\" y=\"{}\" width=\"12\" height=\"12\" fill=\"{}\" "
        "fill-opacity=\"{}\" stroke=\"#333\" stroke-width=\"0.5\"/><text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\">{}</text></g>\n",
        escape(e.name), escape(e.name), fixed(x, 1), fixed(y, 1), e.colour, fixed(e.opacity, 2), fixed(x + 18, 1), fixed(y + 6, 1),
        escape(fit_text(e.name, room)));
  }
  out += "</g>\n";
}

}  // namespace pagecache::chart
