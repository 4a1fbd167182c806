// report.html from hand-built runs: the charts the page promises (counted by their data-*
// marks), bounded size whatever the rows, escaping of hostile names, byte-identical output, and
// no reference to anything outside the page.

#include "report/html_report.hpp"
#include "report/report_activity.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <regex>
#include <string>

using namespace pagecache;
using pagecache::report::report_html;
using pagecache::report::ReportActivity;

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The chart's opening tag, or "" if the page has none of that kind.
std::string chart_tag(const std::string& html, const std::string& kind) {
  std::smatch m;
  return std::regex_search(html, m, std::regex("<svg class=\"chart\" data-chart=\"" + kind + "\"[^>]*>")) ? m.str() : std::string();
}

MemoryState memory(std::int64_t anonymous, std::int64_t cached, std::int64_t dirty) {
  MemoryState s;
  s.total = 16'000'000'000;
  s.anonymous = anonymous;
  s.cached = cached;
  s.dirty = dirty;
  s.active = cached;
  s.free = s.total - anonymous - cached;
  return s;
}

// Two tasks on two hosts: a reads f (2 s), computes; b writes g.
RunResult small_run() {
  RunResult r;
  r.names = {"app", "a", "b"};
  r.hosts = {"h1", "h2"};
  r.timeline = {{0, 1, PhaseKind::Read, 0, 0.0, 2.0, 2'000'000'000, 0, 2'000'000'000},
                {0, 1, PhaseKind::Compute, 0, 2.0, 5.0, 0, 0, 0},
                {0, 2, PhaseKind::Write, 0, 1.0, 3.0, 1'000'000'000, 1'000'000'000, 0}};
  for (int i = 0; i <= 6; ++i) {
    r.memory.push_back({static_cast<double>(i), 0, memory(1'000'000'000, i * 300'000'000, 0)});
    r.memory.push_back({static_cast<double>(i), 1, memory(0, i * 100'000'000, i * 50'000'000)});
  }
  r.files = {"f", "g"};
  r.cache = {{0, 0, 2'000'000'000}, {0, 1, 0}, {2, 0, 2'000'000'000}, {2, 1, 1'000'000'000}};
  r.summary.makespan = 5.0;
  r.summary.end_time = 6.0;
  return r;
}

Scenario scenario() {
  Scenario s;
  s.source = "small.toml";
  s.title = "two tasks";
  return s;
}

ReportActivity activity() {
  ReportActivity a;
  a.on_flush({0, 3.5, FlushCause::Background, 500'000'000});
  a.on_eviction({1, 4.0, 100'000'000});
  a.on_end(6.0);
  return a;
}

}  // namespace

TEST_CASE("report.html draws a memory chart per host, a Gantt row per task, the cache contents and the activity", "[report][html]") {
  const std::string html = report_html(scenario(), small_run(), activity());
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(count(html, "data-chart=\"memory\" data-series=\"5\" data-rows=\"7\"") == 2);
  CHECK_FALSE(chart_tag(html, "gantt").empty());
  CHECK_THAT(chart_tag(html, "gantt"), Catch::Contains("data-series=\"3\" data-rows=\"2\""));
  CHECK(count(html, "<g class=\"gantt-row\">") == 2);
  CHECK(chart_tag(html, "phases").empty());
  // Two I/O phases (a's read, b's write), a bar each, a series per file.
  CHECK_THAT(chart_tag(html, "cache"), Catch::Contains("data-series=\"2\" data-rows=\"2\""));
  // Five causes of writeback and the evictions, up to the bucket holding 6 s.
  CHECK_THAT(chart_tag(html, "activity"), Catch::Contains("data-series=\"6\""));
  // Each series drawn, and named in the legend: 2 x 5 memory + 2 files + 6 activity.
  CHECK(count(html, "class=\"series") == 18);
  CHECK(count(html, "class=\"legend-item\"") == 18 + 3);
  CHECK(count(html, "data-series=\"dirty\"") == 4);  // 2 paths, 2 legend items
  CHECK_THAT(html, Catch::Contains("memory (GB)") && Catch::Contains("time (s)"));
  CHECK_THAT(html, Catch::Contains("small.toml") && Catch::Contains(std::string("pcsim ") + "0."));
}

TEST_CASE("report.html says what was not recorded", "[report][html]") {
  RunResult r = small_run();
  r.cache.clear();
  r.files.clear();
  r.cache_not_recorded = "switched off";
  const std::string html = report_html(scenario(), r, ReportActivity{});
  CHECK(chart_tag(html, "cache").empty());
  CHECK(chart_tag(html, "activity").empty());
  CHECK_THAT(html, Catch::Contains("Not recorded: switched off"));
  CHECK_THAT(html, Catch::Contains("Not recorded: this run had no activity consumer"));
}

TEST_CASE("above 200 tasks, report.html shows the tasks in each phase over time instead of a Gantt chart", "[report][html]") {
  RunResult r = small_run();
  r.timeline.clear();
  r.names = {"t"};
  for (int i = 0; i < 201; ++i) {
    // Task i reads during [i, i + 2): at most two read at once.
    r.names.push_back("p" + std::to_string(i));
    r.timeline.push_back({static_cast<std::uint32_t>(i + 1), 0, PhaseKind::Read, 0, static_cast<double>(i), i + 2.0, 1, 0, 1});
  }
  r.summary.makespan = 202.0;
  const std::string html = report_html(scenario(), r, ReportActivity{});
  CHECK(chart_tag(html, "gantt").empty());
  CHECK(count(html, "gantt-row") == 0);
  CHECK_THAT(chart_tag(html, "phases"), Catch::Contains("data-series=\"3\" data-rows=\"1000\""));
  CHECK_THAT(html, Catch::Contains("201 tasks, more than the 200"));

  r.timeline.resize(200 * 1);  // 200 tasks: a Gantt chart again
  CHECK(count(report_html(scenario(), r, ReportActivity{}), "<g class=\"gantt-row\">") == 200);
}

TEST_CASE("10^6 memory rows make a page of bounded size, saying it was downsampled", "[report][html]") {
  RunResult r = small_run();
  r.memory.clear();
  for (int i = 0; i < 1'000'000; ++i) {
    const std::int64_t wiggle = (i % 7) * 10'000'000;  // a change on every row
    r.memory.push_back({i * 1e-3, 0, memory(1'000'000'000 + wiggle, 2'000'000'000, wiggle)});
  }
  r.summary.end_time = 1000.0;
  const std::string html = report_html(scenario(), r, ReportActivity{});
  CHECK(html.size() < 300'000);
  CHECK_THAT(html, Catch::Contains("Downsampled from 1000000 rows to 1000"));
  CHECK_THAT(chart_tag(html, "memory"), Catch::Contains("data-rows=\"1000\""));
}

TEST_CASE("more than 8 hosts: the first 8 are drawn and the page says so", "[report][html]") {
  RunResult r = small_run();
  r.memory.clear();
  r.hosts.clear();
  for (int h = 0; h < 12; ++h) {
    r.hosts.push_back("h" + std::to_string(h));
    r.memory.push_back({0.0, static_cast<std::uint32_t>(h), memory(0, 0, 0)});
  }
  const std::string html = report_html(scenario(), r, ReportActivity{});
  CHECK(count(html, "data-chart=\"memory\"") == 8);
  CHECK_THAT(html, Catch::Contains("12 hosts: the first 8 are drawn"));
}

TEST_CASE("more than 7 files: the 7 cached most apart and the others together", "[report][html]") {
  RunResult r = small_run();
  r.files.clear();
  r.cache.clear();
  for (std::uint32_t f = 0; f < 10; ++f) r.files.push_back("file" + std::to_string(f));
  for (const std::uint32_t phase : {0u, 2u})
    for (std::uint32_t f = 0; f < 10; ++f) r.cache.push_back({phase, f, (f + 1) * 1'000'000});
  const std::string html = report_html(scenario(), r, ReportActivity{});
  CHECK_THAT(chart_tag(html, "cache"), Catch::Contains("data-series=\"8\" data-rows=\"2\""));
  CHECK_THAT(html, Catch::Contains("data-series=\"3 other files\""));
  CHECK_THAT(html, Catch::Contains("data-series=\"file9\""));
  CHECK_THAT(html, !Catch::Contains("data-series=\"file0\""));  // the smallest
}

TEST_CASE("hostile names are escaped in report.html", "[report][html][escaping]") {
  RunResult r = small_run();
  const std::string hostile = "<script>alert(1)</script> & \"quoted\" 'single'";
  r.names.push_back(hostile);
  for (PhaseRow& p : r.timeline) p.task = static_cast<std::uint32_t>(r.names.size() - 1);
  r.files[0] = hostile;
  r.hosts[0] = hostile;
  Scenario s = scenario();
  s.title = hostile;
  s.source = hostile + "\x01\xff.toml";
  const std::string html = report_html(s, r, activity());
  CHECK(count(html, "<script") == 0);
  CHECK_THAT(html, Catch::Contains("&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;quoted&quot; &#39;single&#39;"));
  CHECK(html.find('\x01') == std::string::npos);
  CHECK(html.find('\xff') == std::string::npos);
}

TEST_CASE("report.html is byte-identical for the same run and refers to nothing outside itself", "[report][html]") {
  const std::string first = report_html(scenario(), small_run(), activity());
  CHECK(first == report_html(scenario(), small_run(), activity()));
  CHECK(first.find("http://") == std::string::npos);
  CHECK(first.find("https://") == std::string::npos);
  CHECK(first.find("src=") == std::string::npos);
  CHECK(first.find("href=") == std::string::npos);
  CHECK(first.find("url(") == std::string::npos);
  CHECK(first.find("@import") == std::string::npos);
}
