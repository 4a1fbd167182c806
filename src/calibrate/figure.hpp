#pragma once
// Figure: one value of the platform and how it was found, from one measurement or the median of
// its repetitions, with their range (the spread a comment shows and a comparison needs).

#include "calibrate/measure.hpp"

#include <functional>
#include <string>

namespace pagecache::calibrate {

/// A value of the platform and how it was found; not `measured`: `how` says why not.
struct Figure {
  double value = 0.0;  ///< bytes per second: the median of its repetitions
  std::string how;
  bool measured = false;
  double spread_pct = 0.0;  ///< (max - min) / median of the repetitions
  double low = 0.0, high = 0.0;  ///< the slowest and the fastest repetition
};

/// One measurement as a Figure, or not measured if it moved nothing.
Figure figure(const Rate& r, std::string how);

/// `once` run `repeat` times (told which, from 0): the median of their rates, and how far they
/// were apart.
Figure repeated(int repeat, const std::function<Rate(int)>& once, const std::string& how);

}  // namespace pagecache::calibrate
