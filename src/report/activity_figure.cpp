#include "report/figures.hpp"

#include "chart/area_chart.hpp"
#include "chart/html_text.hpp"
#include "chart/palette.hpp"

#include <fmt/format.h>

namespace pagecache::report {

namespace {

// In FlushCause's order.
constexpr std::array<std::string_view, ReportActivity::kCauses> kCauseColours = {chart::kVermillion, chart::kReddishPurple, chart::kBlue,
                                                                                 chart::kBluishGreen, chart::kYellow};

std::string bucket_width(double seconds) {
  return seconds < 1.0 ? chart::fixed(seconds * 1e3, 0) + " ms" : chart::fixed(seconds, 3) + " s";
}

}  // namespace

std::string activity_figure(const ReportActivity& a) {
  std::string out = "<h2>Writeback and eviction</h2>\n";
  if (!a.recorded()) return out + "<p class=\"note\">Not recorded: this run had no activity consumer attached.</p>\n";
  const auto& buckets = a.buckets();
  chart::AreaChart c;
  c.kind = "activity";
  c.title = "bytes written back by cause and evicted, per time bucket";
  c.x_title = "time (s)";
  c.y_title = "GB per " + bucket_width(a.width());
  c.x_end = static_cast<double>(buckets.size()) * a.width();
  for (std::size_t b = 0; b < buckets.size(); ++b) c.x.push_back(static_cast<double>(b) * a.width());
  double throttled = 0.0;
  for (std::size_t cause = 0; cause < ReportActivity::kCauses; ++cause) {
    chart::AreaSeries s{"written back: " + std::string(to_string(static_cast<FlushCause>(cause))), kCauseColours[cause], {}};
    for (const auto& bucket : buckets) s.y.push_back(static_cast<double>(bucket.flushed[cause]) / 1e9);
    c.series.push_back(std::move(s));
  }
  chart::AreaSeries evicted{"evicted (line)", chart::kBlack, {}, false, 1.0};
  for (const auto& bucket : buckets) {
    evicted.y.push_back(static_cast<double>(bucket.evicted) / 1e9);
    throttled += bucket.throttled;
  }
  c.series.push_back(std::move(evicted));
  out += fmt::format("<p class=\"note\">Stacked: bytes written back, by cause; the line: clean bytes evicted; summed over hosts, in "
                     "buckets of {}. Writers were held by dirty throttling for {} s in all.</p>\n",
                     bucket_width(a.width()), chart::fixed(throttled, 3));
  return out + chart::area_chart(c);
}

}  // namespace pagecache::report
