#include "calibrate/cold_memory.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

namespace pagecache::calibrate {

namespace {

std::string range_text(const Figure& f) { return fmt::format("{:.0f}-{:.0f} MB/s", f.low / 1e6, f.high / 1e6); }

}  // namespace

ColdFault cold_fault_rate(bool reporting, const Figure& warm, const Figure& cold) {
  ColdFault f;
  if (!reporting) {
    f.why = "no free page reporting here: memory this machine frees stays with it";
  } else if (!warm.measured || !cold.measured) {
    f.why = fmt::format("the write into {} was not measured", warm.measured ? "memory the host took back" : "memory just freed");
  } else if (warm.value - cold.value <= (warm.high - warm.low) + (cold.high - cold.low)) {
    // Medians apart by less than their repetitions' ranges together: no difference to give pcsim.
    f.why = fmt::format("the write into memory the host took back ({}, {}) was not slower than into memory just freed ({}, {}) by more than "
                        "their spreads (the ranges' widths together)",
                        rate_text(cold.value), range_text(cold), rate_text(warm.value), range_text(warm));
  } else {
    f.known = true;
    f.rate = 1.0 / (1.0 / cold.value - 1.0 / warm.value);
  }
  return f;
}

std::string cold_fault_toml(const ColdFault& f, const Figure& warm, const Figure& cold) {
  if (!f.known) return fmt::format("# memory_cold_fault_bw, page_reporting_delay not set: {}\n", f.why);
  std::string out = fmt::format("# the extra time per byte of touching memory the host took back: 1 / (1/{:.0f} - 1/{:.0f} MB/s), the write into "
                                "memory the host took back ({}) and into memory just freed (memory_write_bw; {})\n",
                                cold.value / 1e6, warm.value / 1e6, range_text(cold), range_text(warm));
  out += fmt::format("memory_cold_fault_bw = \"{}\"\n", rate_text(f.rate));
  out += fmt::format("# the kernel's PAGE_REPORTING_DELAY (mm/page_reporting.c: 2 * HZ): freed memory is reported to the host this long after\n"
                     "page_reporting_delay = \"{:g} s\"\n",
                     kPageReportingDelay);
  return out;
}

}  // namespace pagecache::calibrate
