#pragma once
// fio.json and the terse per-job summary `pcsim run` prints for the jobs of a fio job file
// pcsim ran ([fio]; Scenario::fio): what `fio --output-format=json` reports per job that a
// simulation can compute.

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace pagecache::report {

/// A job's I/O in one direction, as fio reports it.
struct FioDirection {
  std::int64_t bytes = 0;
  std::int64_t ios = 0;
  double seconds = 0.0;  ///< from its first request's start to its last's end (fsyncs included)
  double bytes_per_second() const noexcept { return seconds > 0.0 ? static_cast<double>(bytes) / seconds : 0.0; }
  double iops() const noexcept { return seconds > 0.0 ? static_cast<double>(ios) / seconds : 0.0; }
};

struct FioJobResult {
  const FioJobInfo* job = nullptr;
  FioDirection read;
  FioDirection write;
  double seconds = 0.0;  ///< the job's, both directions together
};

/// Each fio job of `scenario`'s results in `result`, in fio's order (from its access rows).
std::vector<FioJobResult> fio_results(const Scenario& scenario, const RunResult& result);

/// The text of fio.json: per job its jobname, groupid, job options and, for reads and writes,
/// io_bytes, io_kbytes, bw_bytes (B/s), bw (KiB/s), iops, runtime (ms) and total_ios, as fio
/// names them. Rates come from the simulated seconds, not from fio's whole milliseconds.
std::string fio_json(const Scenario& scenario, const RunResult& result);

/// A line per job and direction: "NAME: READ: bw=...MiB/s (...MB/s), io=...MiB, iops=..., run=...ms".
std::string fio_summary(const Scenario& scenario, const RunResult& result);

}  // namespace pagecache::report
