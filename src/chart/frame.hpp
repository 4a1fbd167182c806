#pragma once
// What every chart shares: the SVG element marked for tests and tools (data-chart, data-series,
// data-rows), a plot area with its two axes (ticks at round values, titles with units) and a
// legend to the right of it. Coordinates are written with one decimal: a page is the same, byte
// for byte, for the same input.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::chart {

/// An axis: the range it shows and its title, unit included ("time (s)").
struct Axis {
  double lo = 0.0;
  double hi = 1.0;
  std::string title;
};

/// The canvas in pixels, the margins around the plot area (the legend sits in the right one),
/// and the axes.
struct Plot {
  double width = 960.0;
  double height = 340.0;
  double left = 70.0;
  double right = 220.0;
  double top = 14.0;
  double bottom = 46.0;
  Axis x;
  Axis y;

  double plot_width() const noexcept { return width - left - right; }
  double plot_height() const noexcept { return height - top - bottom; }
  /// Pixel column and row of a value (y grows upwards in the data, downwards on screen).
  double px(double v) const noexcept { return left + (v - x.lo) / (x.hi - x.lo) * plot_width(); }
  double py(double v) const noexcept { return top + plot_height() - (v - y.lo) / (y.hi - y.lo) * plot_height(); }
};

/// Tick values at 1, 2 or 5 times a power of ten, about `target` of them from `lo` up to the
/// first at or beyond `hi`: the axis then ends on a tick (see nice_range).
std::vector<double> nice_ticks(double lo, double hi, int target);

/// [lo, hi] widened to the ticks around it; an empty or inverted range becomes [lo, lo + 1].
Axis nice_range(double lo, double hi, std::string title, int target);

/// A tick's label: as many decimals as the tick step needs.
std::string tick_label(double value, double step);

/// The ticks of `axis` drawn over `pixels`, about `target` of them, fewer if their labels would
/// touch: along a horizontal axis each label's width, along a vertical one a line's height, plus
/// a gap, must fit between neighbours. Only ticks inside the axis' range.
std::vector<double> axis_ticks(const Axis& axis, double pixels, bool horizontal, int target);

struct LegendEntry {
  std::string name;
  std::string_view colour;
  double opacity = 1.0;
};

/// The opening tag of a chart's SVG (data-chart = `kind`, data-series, data-rows) with its
/// accessible title; close it with "</svg>".
std::string svg_open(std::string_view kind, std::size_t series, std::size_t rows, const Plot& plot, std::string_view title);

/// The plot's frame: grid lines and labels at the ticks of both axes, and the axis titles.
/// `x_ticks` false leaves the x axis to the caller (a bar chart labels its categories), as
/// `y_ticks` false the y axis (a Gantt chart labels its rows); an empty title is not drawn.
void draw_axes(std::string& out, const Plot& plot, bool x_ticks = true, bool y_ticks = true);

/// The legend, top to bottom in the series' order, in the right margin: one
/// `<g class="legend-item" data-series="name">` per distinct entry (an entry identical to an
/// earlier one, name, colour and opacity, is not repeated), its label shortened to the margin
/// with the full name in its tooltip.
void draw_legend(std::string& out, const Plot& plot, const std::vector<LegendEntry>& entries);

}  // namespace pagecache::chart
