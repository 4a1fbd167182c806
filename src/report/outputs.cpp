#include "report/outputs.hpp"

#include "report/csv_field.hpp"
#include "report/fio_json.hpp"
#include "report/html_report.hpp"
#include "report/output_file.hpp"
#include "report/output_folder.hpp"
#include "report/output_rules.hpp"
#include "text/json_string.hpp"
#include "text/printable.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>
#include <pagecache/version.hpp>

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <map>
#include <string_view>
#include <utility>

// The files one by one are the public API (pagecache/outputs.hpp); write_outputs, which puts
// them in one folder, is report's.
namespace pagecache {

namespace fs = std::filesystem;
using report::append_csv_field;
using report::NamedOutput;
using report::OutputFolder;
using report::OutputOptions;
using report::ReportActivity;
using text::json_string;
using text::printable;

namespace {

// Bytes for a reader: decimal units, one decimal ("235.6 GB"); exact figures are in the files.
std::string readable(std::int64_t bytes) {
  static constexpr std::pair<const char*, double> kUnits[] = {{"TB", 1e12}, {"GB", 1e9}, {"MB", 1e6}, {"kB", 1e3}};
  for (const auto& [name, factor] : kUnits) {
    if (static_cast<double>(bytes) >= factor) return fmt::format("{:.1f} {}", static_cast<double>(bytes) / factor, name);
  }
  return fmt::format("{} B", bytes);
}

void write_file(const fs::path& path, const std::string& text) {
  report::OutputFile out(path.string());
  out.write(text);
  out.commit();
}

// MB/s with one decimal, or three significant digits below 1 MB/s: a slow phase (100 MB over
// an hour) is not shown as 0.0.
std::string readable_rate(double mb_per_s) { return mb_per_s >= 1.0 ? fmt::format("{:.1f}", mb_per_s) : fmt::format("{:.3g}", mb_per_s); }

// A CSV file written as it is formatted: rows go straight into one small fmt::memory_buffer,
// written out and reused whenever it fills, so that neither a string per row nor the whole
// file is ever made in memory.
class CsvFile {
 public:
  // Any path, by the rule of output_file.hpp (a device written through, a file replaced whole).
  explicit CsvFile(const fs::path& path) : file_(path.string()) {}

  fmt::appender out() { return fmt::appender(buffer_); }
  /// A text field and the comma after it (see csv_field.hpp); numbers go through out().
  void field(std::string_view text) {
    append_csv_field(buffer_, text);
    buffer_.push_back(',');
  }
  /// Fields already escaped, by csv_fields().
  void escaped(std::string_view fields) { buffer_.append(fields.data(), fields.data() + fields.size()); }
  /// After each row: writes the buffer out once it holds enough.
  void row_written() {
    if (buffer_.size() >= kFlushAt) flush();
  }
  void close() {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kFlushAt = 1 << 16;
  void flush() {
    file_.write(std::string_view(buffer_.data(), buffer_.size()));
    buffer_.clear();
  }

  report::OutputFile file_;
  fmt::memory_buffer buffer_;
};

// Text fields, each escaped and followed by a comma, as one string.
std::string csv_fields(std::initializer_list<std::string_view> texts) {
  fmt::memory_buffer out;
  for (std::string_view text : texts) {
    append_csv_field(out, text);
    out.push_back(',');
  }
  return fmt::to_string(out);
}

}  // namespace

void write_timeline_csv(const fs::path& path, const RunResult& r) {
  CsvFile csv(path);
  fmt::format_to(csv.out(), "app,task,host,phase,start_s,end_s,bytes,cache_bytes,disk_bytes\n");
  for (const PhaseRow& p : r.timeline) {
    csv.field(r.app_name(p));
    csv.field(r.task_name(p));
    csv.field(r.host_name(p));
    csv.field(to_string(p.phase));
    fmt::format_to(csv.out(), FMT_COMPILE("{:.6f},{:.6f},{},{},{}\n"), p.start, p.end, p.bytes, p.cache_bytes, p.disk_bytes);
    csv.row_written();
  }
  csv.close();
}

void write_memory_csv(const fs::path& path, const RunResult& r) {
  CsvFile csv(path);
  fmt::format_to(csv.out(), "host,time_s,total_bytes,free_bytes,anonymous_bytes,cached_bytes,dirty_bytes,writeback_bytes,active_bytes,inactive_bytes\n");
  for (const MemoryRow& m : r.memory) {
    const MemoryState& s = m.state;
    csv.field(r.host_name(m));
    // Copies in flight hold their pages: counted as cached here, so that the columns add up.
    fmt::format_to(csv.out(), FMT_COMPILE("{:.6f},{},{},{},{},{},{},{},{}\n"), m.time, s.total, s.free, s.anonymous, s.cached + s.reserved,
                   s.dirty, s.writeback, s.active, s.inactive + s.reserved);
    csv.row_written();
  }
  csv.close();
}

void write_cache_csv(const fs::path& path, const RunResult& r) {
  // Every row repeats a phase's app, task and phase and a file's name: each is escaped once
  // here, not once per row.
  std::vector<std::string> phase_fields;
  phase_fields.reserve(r.timeline.size());
  for (const PhaseRow& p : r.timeline) phase_fields.push_back(csv_fields({r.app_name(p), r.task_name(p), to_string(p.phase)}));
  std::vector<std::string> file_fields;
  file_fields.reserve(r.files.size());
  for (const std::string& file : r.files) file_fields.push_back(csv_fields({file}));
  CsvFile csv(path);
  fmt::format_to(csv.out(), "app,task,phase,file,cached_bytes\n");
  for (const CacheRow& c : r.cache) {
    csv.escaped(phase_fields[c.phase]);
    csv.escaped(file_fields[c.file]);
    fmt::format_to(csv.out(), FMT_COMPILE("{}\n"), c.cached);
    csv.row_written();
  }
  csv.close();
}

std::string cache_contents_note(const RunResult& r) {
  return r.cache_not_recorded.empty() ? "cache.csv" : "not recorded: " + r.cache_not_recorded;
}

std::string summary_json(const Scenario& scenario, const RunResult& r) {
  const RunSummary& s = r.summary;
  auto totals = [](const PhaseTotals& t) { return fmt::format("{{\"seconds\": {:.6f}, \"bytes\": {}}}", t.seconds, t.bytes); };
  return fmt::format(
      "{{\n"
      "  \"pcsim_version\": {},\n"
      "  \"scenario\": {},\n"
      "  \"profile\": {},\n"
      "  \"makespan_s\": {:.6f},\n"
      "  \"end_time_s\": {:.6f},\n"
      "  \"phases\": {{\"read\": {}, \"compute\": {}, \"write\": {}}},\n"
      "  \"disk_read_bytes\": {},\n"
      "  \"cache_read_bytes\": {},\n"
      "  \"forced_flush_bytes\": {},\n"
      "  \"periodic_flush_bytes\": {},\n"
      "  \"flushed_bytes\": {},\n"
      "  \"evicted_bytes\": {},\n"
      "  \"peak_dirty_bytes\": {},\n"
      "  \"events\": {},\n"
      "  \"chunk_operations\": {},\n"
      "  \"cache_contents\": {}\n"
      "}}\n",
      json_string(kVersion), json_string(scenario.source), json_string(to_string(scenario.profile)), s.makespan, s.end_time,
      totals(s.read), totals(s.compute), totals(s.write), s.disk_read_bytes, s.cache_read_bytes, s.forced_flush_bytes,
      s.periodic_flush_bytes, s.forced_flush_bytes + s.periodic_flush_bytes, s.evicted_bytes, s.peak_dirty_bytes, s.events,
      s.chunk_operations, json_string(cache_contents_note(r)));
}

std::string timing_json(const RunResult& r) {
  const RunSummary& s = r.summary;
  return fmt::format("{{\n  \"wall_time_s\": {:.6f},\n  \"events\": {},\n  \"events_per_second\": {:.0f}\n}}\n", s.wall_seconds,
                     s.events, s.events_per_second);
}

std::vector<std::string> report::write_outputs(const std::string& dir, const Scenario& scenario, const RunResult& result,
                                       const OutputOptions& options) {
  for (const NamedOutput& f : options.more) {
    if (std::find(std::begin(report::kOutputNames), std::end(report::kOutputNames), f.name) == std::end(report::kOutputNames)) {
      throw Error(fmt::format("'{}' is not one of pcsim's output names", f.name));  // a replaced folder would keep it
    }
  }
  OutputFolder folder(dir);
  const fs::path& staging = folder.staging();
  try {
    write_timeline_csv(staging / "timeline.csv", result);
    write_memory_csv(staging / "memory.csv", result);
    if (result.cache_not_recorded.empty()) write_cache_csv(staging / "cache.csv", result);
    write_file(staging / "summary.json", summary_json(scenario, result));
    write_file(staging / "timing.json", timing_json(result));
    if (!scenario.fio.jobs.empty()) write_file(staging / "fio.json", fio_json(scenario, result));
    if (options.report) {
      write_file(staging / "report.html", report::report_html(scenario, result, options.activity != nullptr ? *options.activity : ReportActivity{}));
    }
    for (const NamedOutput& f : options.more) write_file(staging / f.name, f.text);
  } catch (const ConfigError& e) {
    // A file of the staging folder could not be written (a full disk): --out's folder.
    throw ConfigError(fmt::format("--out {}: {}", dir, e.what()));
  }
  return folder.commit();
}

std::string readable_summary(const Scenario& scenario, const RunResult& r) {
  std::string out;
  // Names as printable(): a control character in one cannot drive the terminal.
  if (!scenario.title.empty()) out += printable(scenario.title) + "\n";
  out += fmt::format("scenario {} (profile {})\n", printable(scenario.source), to_string(scenario.profile));
  std::map<std::uint32_t, std::vector<const PhaseRow*>> by_app;
  std::vector<std::uint32_t> order;
  for (const PhaseRow& p : r.timeline) {
    if (by_app.find(p.app) == by_app.end()) order.push_back(p.app);
    by_app[p.app].push_back(&p);
  }
  constexpr std::size_t kMaxApps = 8;
  for (std::size_t i = 0; i < order.size() && i < kMaxApps; ++i) {
    out += fmt::format("\napp {}\n{:>10} {:>8} {:>10} {:>10} {:>10} {:>9} {:>9}\n", printable(r.names[order[i]]), "task", "phase", "start_s",
                       "end_s", "MB/s", "cache_GB", "disk_GB");
    for (const PhaseRow* p : by_app[order[i]]) {
      const double seconds = p->end - p->start;
      const std::string rate = p->bytes > 0 && seconds > 0 ? readable_rate(static_cast<double>(p->bytes) / seconds / 1e6) : "-";
      out += fmt::format("{:>10} {:>8} {:>10.2f} {:>10.2f} {:>10} {:>9.2f} {:>9.2f}\n", printable(r.task_name(*p)), to_string(p->phase), p->start,
                         p->end, rate, static_cast<double>(p->cache_bytes) / 1e9, static_cast<double>(p->disk_bytes) / 1e9);
    }
  }
  if (order.size() > kMaxApps) out += fmt::format("\n... and {} more applications (see timeline.csv)\n", order.size() - kMaxApps);
  const RunSummary& s = r.summary;
  out += fmt::format(
      "\nmakespan {:.2f} s; read {} from disk and {} from cache; written back {} (forced) + {} (flusher); "
      "evicted {}; peak dirty {}\n",
      s.makespan, readable(s.disk_read_bytes), readable(s.cache_read_bytes), readable(s.forced_flush_bytes),
      readable(s.periodic_flush_bytes), readable(s.evicted_bytes), readable(s.peak_dirty_bytes));
  out += fmt::format("simulated {} events in {:.3f} s of wall time ({:.2f} M events/s)\n", s.events, s.wall_seconds,
                     s.events_per_second / 1e6);
  return out;
}

}  // namespace pagecache
