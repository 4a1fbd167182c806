#include "validate/validation.hpp"

#include "chart/bar_chart.hpp"
#include "chart/html_text.hpp"
#include "chart/page.hpp"
#include "chart/palette.hpp"

#include <pagecache/version.hpp>

#include <fmt/format.h>

#include <cmath>

namespace pagecache::validate {

namespace {

using chart::fixed;

// The paper's metric, as in validation.cpp.
double error_pct(double sim, double real) { return 100.0 * std::abs(sim - real) / real; }

std::string mean_errors(const CaseResult& c) {
  std::string out = fmt::format("mean error: pcsim {} %, WRENCH-cache {} %", fixed(c.mean_error_pct, 1), fixed(c.wrench_mean_error_pct, 1));
  if (c.read_mean_error_pct >= 0) {
    out += fmt::format("; read: pcsim {} %, WRENCH-cache {} %; write: pcsim {} %, WRENCH-cache {} %", fixed(c.read_mean_error_pct, 1),
                       fixed(c.wrench_read_mean_error_pct, 1), fixed(c.write_mean_error_pct, 1), fixed(c.wrench_write_mean_error_pct, 1));
  }
  return out;
}

std::string case_section(const CaseResult& c) {
  std::string out = fmt::format("<h2>{}</h2>\n<p><strong>{}</strong></p>\n", chart::escape(c.name), chart::escape(mean_errors(c)));
  chart::BarChart bars;
  bars.kind = "validate-" + c.name;
  bars.title = c.name + ": real, pcsim and WRENCH-cache durations";
  bars.x_title = c.name.rfind("exp1", 0) == 0 ? "task and phase" : "pipelines and phase (mean per pipeline)";
  bars.y_title = "duration (s)";
  bars.stacked = false;
  bars.plot.bottom = 100;
  bars.series = {{"real", chart::kBlack, {}}, {"pcsim", chart::kBlue, {}}, {"WRENCH-cache", chart::kOrange, {}}};
  std::vector<std::vector<std::string>> rows;
  for (const Figure& f : c.figures) {
    bars.categories.push_back(f.label);
    bars.series[0].values.push_back(f.real);
    bars.series[1].values.push_back(f.simulated);
    bars.series[2].values.push_back(f.wrench);
    rows.push_back({f.label, fixed(f.real, 2), fixed(f.simulated, 2), fixed(error_pct(f.simulated, f.real), 1), fixed(f.wrench, 2),
                    fixed(error_pct(f.wrench, f.real), 1)});
  }
  out += chart::bar_chart(bars);
  out += chart::html_table({"", "real (s)", "pcsim (s)", "error %", "WRENCH-cache (s)", "error %"}, rows);
  if (!c.extra.empty()) {
    std::vector<std::vector<std::string>> extra;
    for (const auto& [key, value] : c.extra) extra.push_back({key, fixed(value, 2)});
    out += "<p>Other figures:</p>\n" + chart::html_table({"figure", "value"}, extra);
  }
  return out;
}

}  // namespace

std::string Report::html() const {
  std::string body = "<h1>pcsim validate: the paper's experiments against the real runs</h1>\n";
  body += fmt::format("<p class=\"note\">Profile {}, pcsim {}. Error: |simulated - real| / real, per phase (Exp 1) or per number of "
                      "pipelines (Exp 2 and 3, the mean over the real repetitions); the mean errors average them.</p>\n",
                      chart::escape(profile), kVersion);
  for (const CaseResult& c : cases) body += case_section(c);
  return chart::html_page("pcsim validate", body);
}

}  // namespace pagecache::validate
