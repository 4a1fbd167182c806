#pragma once
// The rate of writing into the page cache when its pages must be reclaimed from clean cache:
// clean cache written first, memory held until little is free, then a write. The hold fills
// the machine's memory, so the time it takes grows with the memory: estimated first, and not
// measured where it would exceed its budget.

#include "calibrate/calibrate.hpp"
#include "calibrate/scratch.hpp"

#include <cstdint>

namespace pagecache::calibrate {

struct ReclaimSetting {
  std::int64_t target = 0;  ///< bytes written while reclaiming
  std::int64_t chunk = 0;   ///< write() request
  std::int64_t room = 0;    ///< bytes the file system must still have for the clean fill
  double budget = 45.0;     ///< seconds the fill and the hold may take, as estimated
};

/// Measures it, with the figures already measured to estimate the time and to take the part
/// of the write that went into free pages out (memory_write).
Figure reclaimed_write(const Calibration& c, const Scratch& scratch, const ReclaimSetting& setting);

}  // namespace pagecache::calibrate
