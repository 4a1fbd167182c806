#pragma once
// calibrate's NUMA step: the memory steps' copy, first touch and reads of a cached file, made
// again with the measuring threads on one node's CPUs and the memory on that node, then on
// another: the figures of the platform's [hosts.numa] ratios (remote / local).

#include "calibrate/node_binding.hpp"
#include "calibrate/steps.hpp"

#include <filesystem>
#include <functional>

namespace pagecache::calibrate {

/// The measurements the ratios are made of, each run with the calling thread and its memory
/// where measure_numa placed them: calibrate's own (numa_probes), or a test's.
struct NumaProbes {
  /// One thread's copy; before each repetition, `source` runs before the buffer copied from is
  /// allocated and `destination` before the buffer copied into is.
  std::function<Figure(const std::function<void()>& source, const std::function<void()>& destination)> copy;
  /// One thread's first touch of new anonymous memory.
  std::function<Figure()> first_touch;
  /// Writes `file` through the page cache and keeps it cached: its pages where memory is placed.
  std::function<void(const std::filesystem::path& file)> cache;
  /// `threads` threads at once reading `file`, cached, into buffers of their own.
  std::function<Figure(const std::filesystem::path& file, int threads)> read_together;
};

/// calibrate's: copy_figure, first_touch_figure on a node's share of touch_bytes,
/// write_cached and cached_reads_figure, with the session's sizes and repetitions.
NumaProbes numa_probes(const Session& s, int nodes);

/// With two online nodes or more (c.numa.topology): the threads on the first node that has
/// CPUs, the memory on it (local) and on the next online node (remote), each probe both ways,
/// the binding released after, also on an error. With one node, or a placement the system
/// refuses, c.numa says why and the platform gets no [hosts.numa].
void measure_numa(Calibration& c, Session& s, NodeBinding& binding, const NumaProbes& probes);

}  // namespace pagecache::calibrate
