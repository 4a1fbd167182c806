#pragma once
// Bars per category: stacked (the cache contents after each I/O phase, a part per file) or side
// by side (real against simulated durations). Each series is one
// `<g class="series" data-series="name">` holding its bars, one per category.

#include "chart/frame.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace pagecache::chart {

struct BarSeries {
  std::string name;
  std::string_view colour;
  std::vector<double> values;  ///< one per category, in the y axis' unit
};

struct BarChart {
  std::string kind;   ///< data-chart
  std::string title;  ///< the SVG's accessible title
  std::string x_title;
  std::string y_title;
  std::vector<std::string> categories;  ///< labels under the bars (shortened to fit; full in a tooltip)
  std::vector<BarSeries> series;
  bool stacked = true;  ///< false: the series' bars side by side in each category
  Plot plot;            ///< size and margins (its axes are computed; bottom and height grow for long labels)
};

/// The chart as an SVG element; data-rows is the number of categories.
std::string bar_chart(const BarChart& chart);

}  // namespace pagecache::chart
