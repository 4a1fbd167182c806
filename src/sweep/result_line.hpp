#pragma once
// A line of a results file: one finished run of a sweep, as `sweep run` appends it, and the
// check that a line is one. pcsim writes each member of a line in one order, a whole line in
// one write ending with its newline; so a line that is not exactly that shape was not written
// by pcsim (or not for this sweep: its "base" is another fingerprint), and a last line without
// its newline may be dropped only if it is the beginning of such a line (a shard killed
// while writing it).

#include "sweep/sweep.hpp"

#include <pagecache/run.hpp>

#include <string>
#include <string_view>

namespace pagecache::sweep {

/// The figures of a run that ended well, in the order of a line and of results.csv's columns.
inline constexpr const char* kResultFigures[] = {"makespan_s",       "end_time_s",         "read_s",           "compute_s",
                                                 "write_s",          "disk_read_bytes",    "cache_read_bytes", "forced_flush_bytes",
                                                 "periodic_flush_bytes", "evicted_bytes",  "peak_dirty_bytes", "events"};

/// The run's figures (`result`), or its failure (null `result`: `exit_code`, `error`), as one
/// JSON line without its newline: {"id", "base" (the plan's fingerprint), "run", "overrides",
/// "status", "exit_code", the figures or "error", "wall_s", "sim_wall_s"}. `wall`: the run's
/// time in this process, its scenario loaded and its result formatted, beside the
/// simulation's own (sim_wall_s).
std::string result_line(const std::string& fingerprint, const Run& run, const RunResult* result, int exit_code, const std::string& error,
                        double wall);

struct LineCheck {
  std::string id;       ///< the run's, if the line is a result of this sweep
  std::string problem;  ///< else why not, for a person ("not a result pcsim wrote (...)", ...)
};

/// A whole line, without its newline: a result pcsim wrote for the sweep whose base has
/// `fingerprint`? Its members in pcsim's order with pcsim's types, its id the one its
/// overrides make.
LineCheck check_result_line(std::string_view line, std::string_view fingerprint);

/// A last line that lacks its newline: the beginning of a result pcsim wrote for this sweep
/// (or all of one)? Then it may be dropped, its run run again. `problem` says why not.
LineCheck check_cut_result_line(std::string_view partial, std::string_view fingerprint);

}  // namespace pagecache::sweep
