#pragma once
// Memory a virtual machine's host took back (free page reporting): its next first touch waits
// for the host to fault it in again. The platform gets the extra time per byte this costs, from
// writes into memory just freed and into memory free long enough to have been reported.

#include "calibrate/figure.hpp"

#include <string>

namespace pagecache::calibrate {

/// The kernel's PAGE_REPORTING_DELAY (mm/page_reporting.c: 2 * HZ): how long after memory is
/// freed the kernel reports it to the host.
inline constexpr double kPageReportingDelay = 2.0;

/// Not `known`: `why` says why.
struct ColdFault {
  bool known = false;
  double rate = 0.0;  ///< bytes per second: 1 / (1/cold - 1/warm)
  std::string why;
};

/// From the write into memory just freed (`warm`) and into memory the host took back (`cold`):
/// known only with free page reporting on and the medians apart by more than the widths of the
/// repetitions' ranges together (their spreads).
ColdFault cold_fault_rate(bool reporting, const Figure& warm, const Figure& cold);

/// The platform's `memory_cold_fault_bw` and `page_reporting_delay` lines, or why not.
std::string cold_fault_toml(const ColdFault& f, const Figure& warm, const Figure& cold);

}  // namespace pagecache::calibrate
