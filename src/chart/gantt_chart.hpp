#pragma once
// A horizontal Gantt chart: a row per task, its phases as bars along a time axis, coloured by
// kind. Each row is a `<g class="gantt-row">` holding its label and its bars, each bar a
// `<rect data-series="kind">`; the legend names the kinds.

#include "chart/frame.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::chart {

struct GanttBar {
  double start = 0.0;
  double end = 0.0;
  std::uint8_t series = 0;  ///< index into Gantt::series
};

struct GanttRow {
  std::string label;
  std::vector<GanttBar> bars;
};

struct GanttSeries {
  std::string name;
  std::string_view colour;
};

struct Gantt {
  std::string kind = "gantt";  ///< data-chart
  std::string title;           ///< the SVG's accessible title
  std::string x_title;
  std::vector<GanttSeries> series;
  std::vector<GanttRow> rows;  ///< top to bottom
  double x_end = 0.0;
  Plot plot;  ///< width and margins; the height follows from the rows
};

/// The chart as an SVG element; data-rows is the number of rows.
std::string gantt_chart(const Gantt& chart);

}  // namespace pagecache::chart
