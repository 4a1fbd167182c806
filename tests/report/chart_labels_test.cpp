// The charts' labels as a reader sees them: a label longer than its room is shortened with its
// full name in a <title>, never drawn past the SVG's left edge; a legend has one entry per
// distinct series; neighbouring tick labels never overlap, whatever the chart's width. Positions
// are read back from the SVG text; widths are the charts' own estimate (report_browser_test.sh
// measures the drawn text in Chromium).

#include "chart/area_chart.hpp"
#include "chart/bar_chart.hpp"
#include "chart/gantt_chart.hpp"
#include "chart/palette.hpp"
#include "chart/text_width.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <regex>
#include <set>
#include <string>
#include <vector>

using namespace pagecache::chart;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

struct Label {
  double x;           // the anchor
  std::string title;  // the tooltip, "" if none
  std::string shown;
};

// The Gantt's row labels (anchored at their end).
std::vector<Label> row_labels(const std::string& svg) {
  std::vector<Label> out;
  const std::regex re(R"re(<g class="gantt-row"><text class="tick" x="([-0-9.]+)"[^>]*>(?:<title>([^<]*)</title>)?([^<]*)</text>)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1]), (*it)[2], (*it)[3]});
  return out;
}

// The x axis' tick labels (centred on x).
std::vector<Label> x_ticks(const std::string& svg) {
  std::vector<Label> out;
  const std::regex re(R"re(<text class="tick" x="([-0-9.]+)" y="[-0-9.]+" text-anchor="middle">([^<]*)</text>)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back({std::stod((*it)[1]), "", (*it)[2]});
  return out;
}

Gantt gantt_of(const std::vector<std::string>& labels) {
  Gantt g;
  g.title = "phases";
  g.x_title = "time (s)";
  g.x_end = 10.0;
  g.series = {{"read", kBlue}, {"compute", kBluishGreen}, {"write", kVermillion}};
  for (std::size_t i = 0; i < labels.size(); ++i) g.rows.push_back({labels[i], {{double(i), double(i) + 1.0, 1}}});
  return g;
}

}  // namespace

TEST_CASE("fit_text keeps a label that fits, else both its ends around an ellipsis, as many as fit", "[report][chart]") {
  CHECK(fit_text("map_ID0000001", 500.0) == "map_ID0000001");
  const std::string name = "genome-dax-0/fast2bfq_fast2bfq_HEP2_MSP1_Digests_s_1_sequence_1_ID0000002";
  for (const double room : {40.0, 80.0, 150.0, 300.0}) {
    INFO("room " << room);
    const std::string shown = fit_text(name, room);
    const auto dots = shown.find("\u2026");
    REQUIRE(dots != std::string::npos);
    CHECK(text_width(shown) <= room);
    const std::string head = shown.substr(0, dots), tail = shown.substr(dots + 3);
    CHECK(name.rfind(head, 0) == 0);
    CHECK(name.substr(name.size() - tail.size()) == tail);
    // Not shorter than need be: one more character of the start or the end would not fit.
    CHECK(text_width(name.substr(0, head.size() + 1) + "\u2026" + tail) > room);
    CHECK(text_width(head + "\u2026" + name.substr(name.size() - tail.size() - 1)) > room);
  }
  CHECK(text_width("mmmm") > text_width("iiii"));
  CHECK(fit_text(name, 1.0) == "\u2026");
}

TEST_CASE("a Gantt row label longer than its room is shortened with a <title> of its full name, never past the left edge",
          "[report][chart]") {
  const std::string huge(300, 'W');
  const std::vector<std::string> names = {"a/t1", "genome-dax-0/map_map_HEP2_MSP1_Digests_s_1_sequence_1_ID0000023", huge,
                                          "bacass/NFCORE_BACASS.BACASS.FASTQC_2 \u00e9\u00e9\u00e9"};
  for (const double width : {480.0, 960.0, 1600.0}) {
    INFO("width " << width);
    Gantt g = gantt_of(names);
    g.plot.width = width;
    const std::vector<Label> labels = row_labels(gantt_chart(g));
    REQUIRE(labels.size() == names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
      INFO(names[i]);
      CHECK(labels[i].title == names[i]);
      // Anchored at its end: it starts its width left of the anchor, at or right of x = 0.
      CHECK(labels[i].x - text_width(labels[i].shown) >= 0.0);
      if (labels[i].shown != names[i]) CHECK(labels[i].shown.find("\u2026") != std::string::npos);
    }
    CHECK(labels[0].shown == names[0]);
    CHECK(labels[2].shown != huge);
  }
  // The label area grows to fit a name of moderate length whole rather than shorten it.
  const std::vector<Label> moderate = row_labels(gantt_chart(gantt_of({"genome-dax-0/map_map_HEP2_MSP1_ID0000023"})));
  REQUIRE(moderate.size() == 1);
  CHECK(moderate[0].shown == "genome-dax-0/map_map_HEP2_MSP1_ID0000023");
}

TEST_CASE("a legend has one entry per distinct series, and long names sharing a start stay told apart", "[report][chart]") {
  BarChart same;
  same.kind = "cache";
  same.categories = {"p1", "p2"};
  for (int i = 0; i < 6; ++i) same.series.push_back({"input.dat", kBlue, {1.0, 2.0}});
  const std::string one = bar_chart(same);
  CHECK(count(one, "<g class=\"legend-item\"") == 1);
  CHECK(count(one, "<g class=\"series\"") == 6);  // the bars are all there

  BarChart distinct = same;
  std::set<std::string> shown;
  for (int i = 0; i < 6; ++i)
    distinct.series[i] = {fmt::format("HEP2_MSP1_Digests_s_1_sequence_{}.sfq", i + 1), kPalette[i], {1.0, 2.0}};
  const std::string six = bar_chart(distinct);
  CHECK(count(six, "<g class=\"legend-item\"") == 6);
  const std::regex text(R"re(<g class="legend-item"[^>]*><title>([^<]*)</title><rect[^>]*/><text x="([-0-9.]+)"[^>]*>([^<]*)</text>)re");
  for (auto it = std::sregex_iterator(six.begin(), six.end(), text); it != std::sregex_iterator(); ++it) {
    shown.insert((*it)[3]);
    CHECK(std::stod((*it)[2]) + text_width((*it)[3].str()) <= 960.0);  // inside the SVG
  }
  CHECK(shown.size() == 6);

  // The same name in another colour is another series: both stay.
  same.series[5].colour = kOrange;
  CHECK(count(bar_chart(same), "<g class=\"legend-item\"") == 2);
}

TEST_CASE("tick labels along the time axis never overlap, at any width and range", "[report][chart]") {
  for (const double end : {0.0037, 1.0, 140.013, 12345.678, 86400.0, 3.6e6}) {
    for (double width = 300.0; width <= 2000.0; width += 50.0) {
      INFO("end " << end << ", width " << width);
      AreaChart c;
      c.kind = "memory";
      c.x = {0.0, end / 2};
      c.x_end = end;
      c.series = {{"free", kBlack, {1.0, 2.0}}};
      c.plot.width = width;
      const std::vector<Label> ticks = x_ticks(area_chart(c));
      REQUIRE(!ticks.empty());
      if (c.plot.plot_width() >= 250) CHECK(ticks.size() >= 3);  // thinned, not emptied
      for (std::size_t i = 1; i < ticks.size(); ++i) {
        const double right_of_previous = ticks[i - 1].x + text_width(ticks[i - 1].shown) / 2;
        const double left_of_this = ticks[i].x - text_width(ticks[i].shown) / 2;
        CHECK(right_of_previous < left_of_this);
      }
    }
  }
}

TEST_CASE("rotated category labels are thinned so that neighbours do not overlap, and stay right of the left edge",
          "[report][chart]") {
  const double pi = std::acos(-1.0);
  for (const std::size_t n : {3u, 20u, 100u}) {
    for (const double width : {480.0, 960.0, 1600.0}) {
      INFO(n << " categories, width " << width);
      BarChart c;
      c.kind = "cache";
      for (std::size_t i = 0; i < n; ++i) c.categories.push_back(fmt::format("genome-dax-0/map_map_ID{:07} write", i));
      c.series = {{"f", kBlue, std::vector<double>(n, 1.0)}};
      c.plot.width = width;
      const std::string svg = bar_chart(c);
      std::smatch size;
      REQUIRE(std::regex_search(svg, size, std::regex(R"re(<svg [^>]* height="([0-9]+)")re")));
      const double height = std::stod(size[1]);
      const std::regex re(R"re(<text class="tick" transform="translate\(([-0-9.]+) ([-0-9.]+)\) rotate\(-35\)"[^>]*><title>([^<]*)</title>([^<]*)</text>)re");
      std::vector<double> anchors;
      for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it) {
        const double x = std::stod((*it)[1]), w = text_width((*it)[4].str());
        anchors.push_back(x);
        CHECK(x - w * std::cos(35 * pi / 180) >= 0.0);
        CHECK(std::stod((*it)[2]) + w * std::sin(35 * pi / 180) <= height - 20);  // above the axis title
      }
      REQUIRE(!anchors.empty());
      // Every category has its full name as a tooltip: on its label, or on its column if unlabelled.
      CHECK(count(svg, "<rect class=\"category\"") + anchors.size() == n);
      if (n == 100) CHECK(anchors.size() < n);  // thinned
      // Parallel labels: apart across their baselines by at least a line's height.
      for (std::size_t i = 1; i < anchors.size(); ++i) CHECK((anchors[i] - anchors[i - 1]) * std::sin(35 * pi / 180) >= line_height());
    }
  }
}
