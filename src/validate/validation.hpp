#pragma once
// `pcsim validate`: runs the paper's experiments with the shipped scenarios and compares them
// with the real measurements (validation/paper/, copied from the paper's repository), with the
// paper's metric: per-phase absolute relative error |sim - real| / real, and its mean; for
// Exp 2 and 3 per number of pipelines n against the mean of the 5 real repetitions, then the
// mean over n. WRENCH-cache's published figures are shown beside pcsim's.

#include <string>
#include <utility>
#include <vector>

namespace pagecache::validate {

struct Options {
  std::string data_dir;      ///< validation/paper
  std::string scenario_dir;  ///< scenarios/paper
  std::string profile;       ///< "" : the scenarios' own
  std::vector<std::pair<std::string, std::string>> overrides;
  /// Page-cache switches forced on every host (ablations), e.g. {"background_writeback", false}.
  std::vector<std::pair<std::string, bool>> switches;
};

/// One compared duration: a phase of Exp 1, or for Exp 2 and 3 the mean read or write time at
/// one number of pipelines. Seconds.
struct Figure {
  std::string label;  ///< "task 1 read", "n=8 write"
  double real = 0.0;
  double simulated = 0.0;  ///< pcsim's
  double wrench = 0.0;     ///< WRENCH-cache's published figure
};

struct CaseResult {
  std::string name;
  std::vector<Figure> figures;  ///< what the mean errors are computed from, in the table's order
  double mean_error_pct = 0.0;
  double read_mean_error_pct = -1.0;   ///< Exp 2/3 only
  double write_mean_error_pct = -1.0;  ///< Exp 2/3 only
  double wrench_mean_error_pct = 0.0;
  double wrench_read_mean_error_pct = -1.0;
  double wrench_write_mean_error_pct = -1.0;
  std::vector<std::pair<std::string, double>> extra;  ///< other figures (memory profile, cache contents)
  std::string table;                                  ///< printable detail
};

struct Report {
  std::string profile;
  std::vector<CaseResult> cases;
  std::string text() const;
  std::string json() const;
  /// The same as one self-contained HTML page (validation_html.cpp): per case a table of the
  /// figures with their errors, the mean errors, and a bar chart of real, pcsim and
  /// WRENCH-cache side by side (`<svg class="chart" data-chart="validate-<case>">`).
  std::string html() const;
};

/// Reads and checks the data (paper_data.hpp), then simulates and compares; a fault in the data
/// is a ConfigError naming its file, line and column.
Report run(const Options& options);

/// Throws InvariantError naming the case and figure if a number of `report` is NaN or infinite:
/// run() never makes one, and JSON and HTML cannot hold them. json() and html() check first.
void check_finite(const Report& report);

}  // namespace pagecache::validate
