#include "calibrate_command.hpp"

#include "calibrate/calibrate.hpp"
#include "calibrate/measure.hpp"
#include "report/output_file.hpp"
#include "status_line.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <cstdio>

namespace pcsim {

namespace cal = pagecache::calibrate;

void add_calibrate_command(CLI::App& app, CalibrateCommand& c) {
  c.app = app.add_subcommand("calibrate",
                             "measure this machine (its disk under --dir, its memory and page cache, its kernel's settings) and write a "
                             "platform file whose every value names its measurement");
  c.app->add_option("--dir", c.dir, "a folder on the file system to measure; calibrate writes its files in a folder of its own there and "
                                    "removes them")
      ->required();
  c.app->add_option("--out", c.out, "write the platform file here (replaced if it exists) and a summary to the standard output; "
                                    "without: the platform file to the standard output, the summary to the standard error");
  c.app->add_flag("--quick", c.quick, "small files and short measurements (under 20 s), rough figures, no measurement of reclaim");
  c.app->add_option("--size", c.size, "bytes per measuring file, e.g. \"256 MB\" (default 1 GiB, 64 MiB with --quick)");
  c.app->add_option("--streams", c.streams, "concurrent streams for the aggregate rates (default 4, 2 with --quick)")->check(CLI::Range(1, 64));
  c.app->add_option("--repeat", c.repeat, "measurements of each figure, of which the median is taken (default 3, 1 with --quick)")
      ->check(CLI::Range(1, 20));
}

namespace {

// The NUMA ratios with the two figures of each; nothing where they were not measured (a note says why).
void print_numa(std::FILE* summary, const cal::NumaFigures& n) {
  if (!n.measured) return;
  for (const cal::NumaKey& k : cal::kNumaKeys) {
    const cal::NumaPair& p = n.*k.pair;
    const std::string what = fmt::format("{}, node {} / node {} memory", k.what, n.remote, n.local);
    if (p.measured()) fmt::print(summary, "  {:<48} {:>8.3f}  ({:.0f} / {:.0f} MB/s)\n", what, p.ratio(), p.remote.value / 1e6, p.local.value / 1e6);
    else fmt::print(summary, "  {:<48} {:>8}  ({})\n", what, "-", p.local.measured ? p.remote.how : p.local.how);
  }
}

// Each figure on a line, the NUMA ratios, then the notes.
void print_summary(std::FILE* summary, const cal::Calibration& result) {
  fmt::print(summary, "pcsim calibrate: {:.0f} s on {} ({} cores, {} MiB of memory), files on {}\n", result.seconds, result.system.hostname,
             result.system.cores, result.system.memory_total >> 20, result.system.file_system);
  const auto line = [&](const char* what, const cal::Figure& f) {
    if (f.measured && f.spread_pct > 0.0) fmt::print(summary, "  {:<48} {:>8.0f} MB/s  (spread {:.0f} %)\n", what, f.value / 1e6, f.spread_pct);
    else if (f.measured) fmt::print(summary, "  {:<48} {:>8.0f} MB/s\n", what, f.value / 1e6);
    else fmt::print(summary, "  {:<48} {:>8}  ({})\n", what, "-", f.how);
  };
  line("disk read, one stream (O_DIRECT)", result.disk_read);
  line(fmt::format("disk read, {} streams", result.streams).c_str(), result.disk_aggregate_read);
  line("writeback, one file", result.writeback);
  line(fmt::format("writeback, {} files", result.streams).c_str(), result.aggregate_writeback);
  line("disk write, one stream (O_DIRECT, comparison)", result.disk_write);
  line(fmt::format("disk write, {} streams (comparison)", result.streams).c_str(), result.disk_aggregate_write);
  line("buffered read from disk (comparison)", result.buffered_read);
  line("cached read, reused buffer", result.memory_read);
  line("cached read, new buffer", result.memory_read_fresh);
  line("write into the cache, memory just freed", result.memory_write);
  if (result.memory_write_cold.measured) line("write into the cache, memory the host took back", result.memory_write_cold);
  line("write into the cache, reclaiming", result.memory_reclaimed_write);
  line("first touch of new memory", result.first_touch);
  line("cached reads, every core", result.memory_aggregate_read);
  line("writes into the cache, every core", result.memory_aggregate_write);
  line("memcpy, one thread", result.copy_one);
  line("memcpy, every core", result.copy_all);
  print_numa(summary, result.numa);
  for (const std::string& note : result.notes) fmt::print(summary, "  note: {}\n", note);
}

}  // namespace

int run_calibrate_command(const CalibrateCommand& c) {
  if (c.app->count("--out") > 0) pagecache::report::check_output_file(c.out, "--out");  // `--out ''` is refused, not ignored
  cal::Options options;
  options.dir = c.dir;
  options.quick = c.quick;
  options.streams = c.streams;
  options.repeat = c.repeat;
  if (!c.size.empty()) {
    try {
      options.size = pagecache::units::parse_size(c.size);
    } catch (const pagecache::ConfigError& e) {
      throw pagecache::ConfigError(fmt::format("--size: {}", e.what()));
    }
    if (options.size < (1 << 20)) throw pagecache::ConfigError(fmt::format("--size {}: at least 1 MiB", c.size));
  }
  StatusLine status(true);
  options.progress = [&](const std::string& step, int number, int steps) {
    if (status.due(true)) status.show(fmt::format("calibrate: {}/{} {}", number, steps, step));
  };
  cal::install_stop_handlers();
  cal::Calibration result;
  try {
    result = cal::calibrate(options);
  } catch (...) {
    status.clear();
    throw;
  }
  status.clear();
  const std::string toml = cal::platform_toml(result);
  print_summary(c.out.empty() ? stderr : stdout, result);
  if (c.out.empty()) {
    fmt::print("{}", toml);
  } else {
    pagecache::report::write_output_file(c.out, toml, "--out");
    fmt::print("platform: {}\n", c.out);
  }
  return 0;
}

}  // namespace pcsim
