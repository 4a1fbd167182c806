#include "report/html_report.hpp"
#include "report/output_rules.hpp"
#include "report/outputs.hpp"
#include "report/report_activity.hpp"
#include "report/trace_json.hpp"

#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>

#include <optional>
#include <utility>

namespace pagecache {

struct RunOutputs::Recorders {
  std::optional<report::TraceJson> trace;
  std::optional<report::ReportActivity> activity;  // report.html's activity chart
};

RunOutputs::RunOutputs(OutputSettings settings) : settings_(settings), recorders_(std::make_unique<Recorders>()) {
  if (settings_.trace) recorders_->trace.emplace(settings_.trace_max_bytes);
  if (settings_.report) recorders_->activity.emplace();
}

RunOutputs::~RunOutputs() = default;

bool RunOutputs::writes_trace() const noexcept { return settings_.trace; }

void RunOutputs::attach(RunOptions& options) {
  if (recorders_->trace) options.consumers.push_back(&*recorders_->trace);
  if (recorders_->activity) options.consumers.push_back(&*recorders_->activity);
}

std::vector<std::string> RunOutputs::write(const std::string& dir, const Scenario& scenario, const RunResult& result) {
  if (written_) throw Error("RunOutputs::write: the outputs of a run are written once (its recorders are freed as it writes)");
  written_ = true;
  report::OutputOptions options{.report = settings_.report, .activity = recorders_->activity ? &*recorders_->activity : nullptr, .more = {}};
  if (recorders_->trace) {
    // The trace's events are freed once its text is made: a large trace is not held twice
    // while the other files are written.
    options.more.push_back({"trace.json", recorders_->trace->text(scenario.source)});
    trace_truncated_ = recorders_->trace->truncated();
    recorders_->trace.reset();
  }
  return report::write_outputs(dir, scenario, result, options);
}

std::string RunOutputs::report_html(const Scenario& scenario, const RunResult& result) const {
  if (!recorders_->activity) throw ConfigError("RunOutputs::report_html: these outputs were made without a report (OutputSettings::report)");
  if (written_) throw Error("RunOutputs::report_html: after write(), the report's recorder is freed");
  return report::report_html(scenario, result, *recorders_->activity);
}

void check_output_folder(const std::string& dir, const std::string& scenario_file) { report::check_output_folder(dir, scenario_file); }

}  // namespace pagecache
