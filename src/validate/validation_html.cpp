#include "validate/validation.hpp"

#include "chart/bar_chart.hpp"
#include "chart/html_text.hpp"
#include "chart/page.hpp"
#include "chart/palette.hpp"

#include <pagecache/version.hpp>

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

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

// Real, pcsim and WRENCH-cache side by side for `figures`, labelled by `label` of each.
std::string bars_of(const std::string& kind, const std::string& title, const std::string& x_title, const std::vector<const Figure*>& figures,
                    const std::function<std::string(const Figure&)>& label) {
  chart::BarChart bars;
  bars.kind = kind;
  bars.title = title;
  bars.x_title = x_title;
  bars.y_title = "duration (s)";
  bars.stacked = false;
  bars.plot.bottom = 100;
  bars.series = {{"real", chart::kBlack, {}}, {"pcsim", chart::kBlue, {}}, {"WRENCH-cache", chart::kOrange, {}}};
  for (const Figure* f : figures) {
    bars.categories.push_back(label(*f));
    bars.series[0].values.push_back(f->real);
    bars.series[1].values.push_back(f->simulated);
    bars.series[2].values.push_back(f->wrench);
  }
  return chart::bar_chart(bars);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string case_section(const CaseResult& c) {
  std::string out = fmt::format("<h2>{}</h2>\n<p><strong>{}</strong></p>\n", chart::escape(c.name), chart::escape(mean_errors(c)));
  std::vector<const Figure*> all, reads, writes;
  std::vector<std::vector<std::string>> rows;
  for (const Figure& f : c.figures) {
    all.push_back(&f);
    (ends_with(f.label, " read") ? reads : writes).push_back(&f);
    rows.push_back({f.label, fixed(f.real, 2), fixed(f.simulated, 2), fixed(error_pct(f.simulated, f.real), 1), fixed(f.wrench, 2),
                    fixed(error_pct(f.wrench, f.real), 1)});
  }
  if (c.read_mean_error_pct < 0) {
    out += bars_of("validate-" + c.name, c.name + ": real, pcsim and WRENCH-cache durations", "task and phase", all,
                   [](const Figure& f) { return f.label; });
  } else {
    // Per number of pipelines, reads and writes apart: 2 x 32 groups of bars do not fit one chart.
    const auto n_only = [](const Figure& f) { return f.label.substr(0, f.label.find(' ')); };
    for (const auto& [phase, figures] : {std::pair{"read", &reads}, std::pair{"write", &writes}}) {
      out += bars_of(fmt::format("validate-{}-{}", c.name, phase), fmt::format("{}: {} time per pipeline", c.name, phase),
                     fmt::format("pipelines (mean {} time per pipeline)", phase), *figures, n_only);
    }
  }
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
  check_finite(*this);
  std::string body = "<h1>pcsim validate: the paper's experiments against the real runs</h1>\n";
  body += fmt::format("<p class=\"note\">Profile {}, pcsim {}. Error: |simulated - real| / real, per phase (Exp 1) or per number of "
                      "pipelines (Exp 2 and 3, the mean over the real repetitions); the mean errors average them.</p>\n",
                      chart::escape(profile), kVersion);
  for (const CaseResult& c : cases) body += case_section(c);
  return chart::html_page("pcsim validate", body);
}

}  // namespace pagecache::validate
