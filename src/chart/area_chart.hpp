#pragma once
// A step chart over time: stacked areas (a memory profile: each row holds until the next) and,
// above them, lines that are not stacked. Each series is one SVG path,
// `<path class="series" data-series="name">`, so a page stays small whatever the points.

#include "chart/frame.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::chart {

struct AreaSeries {
  std::string name;
  std::string_view colour;
  std::vector<double> y;  ///< one value per x, in the y axis' unit
  bool stacked = true;    ///< false: a line over the stack
  double opacity = 0.85;
};

struct AreaChart {
  std::string kind;   ///< data-chart
  std::string title;  ///< the SVG's accessible title
  std::string x_title;
  std::string y_title;
  /// Where each step starts, ascending; the last step ends at x_end.
  std::vector<double> x;
  double x_end = 0.0;
  std::vector<AreaSeries> series;  ///< stacked ones bottom to top, in legend order
  Plot plot;                       ///< size and margins (its axes are computed)
};

/// The chart as an SVG element; data-rows is the number of steps drawn.
std::string area_chart(const AreaChart& chart);

}  // namespace pagecache::chart
