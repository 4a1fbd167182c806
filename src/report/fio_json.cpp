#include "report/fio_json.hpp"

#include "text/json_string.hpp"

#include <pagecache/version.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace pagecache::report {

namespace {

using text::json_string;

// The span of a job's rows in one direction, and their bytes.
struct Span {
  std::int64_t bytes = 0;
  double start = std::numeric_limits<double>::infinity();
  double end = -std::numeric_limits<double>::infinity();
  void add(const PhaseRow& row) {
    bytes += row.bytes;
    start = std::min(start, row.start);
    end = std::max(end, row.end);
  }
  double seconds() const noexcept { return end > start ? end - start : 0.0; }
};

std::string options_json(const std::vector<std::pair<std::string, std::string>>& options) {
  std::string out = "{";
  for (std::size_t i = 0; i < options.size(); ++i) {
    out += fmt::format("{}{}: {}", i == 0 ? "" : ", ", json_string(options[i].first), json_string(options[i].second));
  }
  return out + "}";
}

// fio's object of one direction; one the job did not do is all zeros, as fio writes it.
std::string direction_json(const FioDirection& d) {
  const long long rate = std::llround(d.bytes_per_second());
  return fmt::format(
      "{{\"io_bytes\": {}, \"io_kbytes\": {}, \"bw_bytes\": {}, \"bw\": {}, \"iops\": {:.6f}, \"runtime\": {}, \"total_ios\": {}}}", d.bytes,
      d.bytes >> 10, rate, rate / 1024, d.iops(), std::llround(d.seconds * 1000.0), d.ios);
}

}  // namespace

std::vector<FioJobResult> fio_results(const Scenario& scenario, const RunResult& result) {
  // Each job's access rows ("io:FILE[epoch N]"; not its layouts' in a memory cgroup), by its
  // application's name.
  std::unordered_map<std::string, std::pair<Span, Span>> spans;
  for (const FioJobInfo& job : scenario.fio.jobs) spans.emplace(job.app, std::pair<Span, Span>{});
  for (const PhaseRow& row : result.timeline) {
    const auto it = spans.find(result.app_name(row));
    const std::string& task = result.task_name(row);
    if (it == spans.end() || task.rfind("io:", 0) != 0 || task.find("[epoch ") == std::string::npos) continue;
    if (row.phase == PhaseKind::Read) it->second.first.add(row);
    if (row.phase == PhaseKind::Write) it->second.second.add(row);
  }
  std::vector<FioJobResult> results;
  results.reserve(scenario.fio.jobs.size());
  for (const FioJobInfo& job : scenario.fio.jobs) {
    const auto& [read, write] = spans.at(job.app);
    FioJobResult r;
    r.job = &job;
    r.read = {.bytes = read.bytes, .ios = read.bytes > 0 ? job.read_ios : 0, .seconds = read.seconds()};
    r.write = {.bytes = write.bytes, .ios = write.bytes > 0 ? job.write_ios : 0, .seconds = write.seconds()};
    const double start = std::min(read.start, write.start);
    const double end = std::max(read.end, write.end);
    r.seconds = end > start ? end - start : 0.0;
    results.push_back(r);
  }
  return results;
}

std::string fio_json(const Scenario& scenario, const RunResult& result) {
  std::string jobs;
  for (const FioJobResult& r : fio_results(scenario, result)) {
    jobs += fmt::format(
        "{}    {{\"jobname\": {}, \"groupid\": {}, \"error\": 0, \"pcsim_application\": {}, \"job options\": {},\n"
        "     \"read\": {},\n     \"write\": {},\n     \"job_runtime\": {}}}",
        jobs.empty() ? "" : ",\n", json_string(r.job->jobname), r.job->groupid, json_string(r.job->app), options_json(r.job->options),
        direction_json(r.read), direction_json(r.write), std::llround(r.seconds * 1000.0));
  }
  return fmt::format("{{\n  \"pcsim_version\": {},\n  \"simulated\": true,\n  \"job_file\": {},\n  \"global options\": {},\n  \"jobs\": [\n{}\n  ]\n}}\n",
                     json_string(kVersion), json_string(scenario.fio.file), options_json(scenario.fio.global_options), jobs);
}

std::string fio_summary(const Scenario& scenario, const RunResult& result) {
  std::string out = "fio jobs (simulated):\n";
  for (const FioJobResult& r : fio_results(scenario, result)) {
    for (const auto& [label, d] : {std::pair{"READ", &r.read}, std::pair{"WRITE", &r.write}}) {
      if (d->bytes == 0) continue;
      out += fmt::format("  {}: {}: bw={:.1f}MiB/s ({:.1f}MB/s), io={:.1f}MiB, iops={:.0f}, run={:.0f}ms\n", r.job->app, label,
                         d->bytes_per_second() / 1048576.0, d->bytes_per_second() / 1e6, static_cast<double>(d->bytes) / 1048576.0, d->iops(),
                         d->seconds * 1000.0);
    }
  }
  return out;
}

}  // namespace pagecache::report
