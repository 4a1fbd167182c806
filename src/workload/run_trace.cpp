#include "workload/run_trace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <utility>

namespace pagecache::workload {

namespace {

// A row per file after each I/O phase (two per task, and one per access and epoch), unless that
// is too many: empty, or why not.
std::string why_cache_contents_not_recorded(const RunOptions& options, std::size_t phases, std::size_t files) {
  const std::size_t rows = phases * files;
  if (!options.cache_contents) return "switched off";
  if (rows > options.max_cache_rows) {
    return fmt::format("{} rows ({} I/O phases x {} files) would exceed the limit of {}", rows, phases, files, options.max_cache_rows);
  }
  return {};
}

}  // namespace

RunTrace::RunTrace(const RunOptions& options, FairShare& share, const Platform& platform, std::size_t rows, std::size_t io_phases)
    : RunTrace(options, share, platform, rows, io_phases, why_cache_contents_not_recorded(options, io_phases, platform.files().size())) {}

RunTrace::RunTrace(const RunOptions& options, FairShare& share, const Platform& platform, std::size_t rows, std::size_t io_phases,
                   std::string not_recorded)
    : platform_(platform),
      record_cache_(not_recorded.empty()),
      recorder_(rows, record_cache_ ? io_phases * platform.files().size() : 0, std::move(not_recorded)) {
  std::vector<TraceSink*> all{&recorder_};
  all.insert(all.end(), options.consumers.begin(), options.consumers.end());
  sink_ = all.size() == 1 ? all.front() : &fanouts_.emplace_back(std::move(all));
  const auto one_of = [this](std::vector<TraceSink*> sinks) -> TraceSink* {
    if (sinks.empty()) return nullptr;
    return sinks.size() == 1 ? sinks.front() : &fanouts_.emplace_back(std::move(sinks));
  };
  TraceSink* low = one_of(options.consumers);
  std::vector<TraceSink*> of_flows;
  std::copy_if(options.consumers.begin(), options.consumers.end(), std::back_inserter(of_flows), [](const TraceSink* c) { return c->wants_flows(); });
  share.set_trace(one_of(std::move(of_flows)));
  const std::vector<Host*>& hosts = platform.hosts();
  for (std::uint32_t i = 0; i < hosts.size(); ++i) {
    hosts[i]->set_trace(low, i);
    host_index_.emplace(hosts[i], i);
  }
  std::vector<std::string> files;
  files.reserve(platform.files().size());
  for (const PlacedFile& f : platform.files()) files.push_back(f.host->file_name(f.ref));
  sink_->on_start({.hosts = platform.host_names(), .files = files});
}

std::uint32_t RunTrace::report_phase(std::string_view app, std::string_view task, const Host& host, PhaseKind kind, double start, double end,
                                     const Moved& moved) {
  const std::uint32_t row = phases_++;
  sink_->on_phase({.row = row, .host = host_index_.at(&host), .app = app, .task = task, .kind = kind, .start = start, .end = end,
                   .bytes = moved.bytes, .cache_bytes = moved.cache_bytes, .disk_bytes = moved.disk_bytes});
  return row;
}

void RunTrace::record_cache_contents(std::uint32_t phase) {
  const std::vector<PlacedFile>& files = platform_.files();
  cached_.resize(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) cached_[i] = files[i].host->cached(files[i].ref);
  sink_->on_cache_contents({.phase_row = phase, .cached = cached_});
}

}  // namespace pagecache::workload
