#pragma once
// NumaFigures: how fast calibrate's memory measurements go with the other NUMA node's memory,
// over the same with the measuring threads' own node's: one thread's copy, one thread's first
// touch, and all of a node's CPUs reading together. The platform's [hosts.numa] section, and
// the notes on it. Ratios are written as measured, one above 1 included (with a note).

#include "calibrate/figure.hpp"
#include "calibrate/numa_topology.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::calibrate {

/// What calibrate says and notes on a machine of one node.
/// The most NUMA nodes pcsim's hosts have ([hosts.numa] nodes; cache::kMaxNodes).
inline constexpr std::size_t kMaxModelledNodes = 2;
inline constexpr std::string_view kOneNumaNode = "one NUMA node: no remote memory to measure; the platform has no [hosts.numa]";

/// One measurement with the memory on the measuring threads' node (local) and on the other (remote).
struct NumaPair {
  std::string placement;  ///< where the threads and the memory were
  Figure local, remote;
  bool measured() const { return local.measured && remote.measured && local.value > 0.0; }
  double ratio() const { return remote.value / local.value; }
};

struct NumaFigures {
  NumaTopology topology;
  bool measured = false;
  std::string why;            ///< not measured: why (one node, a system call refused)
  std::string release_failed;  ///< the binding could not be undone: what failed (empty: it was)
  int local = 0;              ///< the node whose CPUs ran the measurements
  int remote = 0;             ///< the other node, whose memory is remote
  int threads = 0;            ///< the reads together: node `local`'s CPUs this process may use
  NumaPair copy, first_touch, aggregate_read;
};

/// A ratio's platform key, what it measures, and its pair.
struct NumaKey {
  const char* key;
  const char* what;
  NumaPair NumaFigures::*pair;
};
inline constexpr NumaKey kNumaKeys[] = {{"remote_copy_ratio", "copy, one thread", &NumaFigures::copy},
                                        {"remote_first_touch_ratio", "first touch, one thread", &NumaFigures::first_touch},
                                        {"remote_aggregate_ratio", "cached reads, a node's CPUs", &NumaFigures::aggregate_read}};

/// The [hosts.numa] section, each ratio under how it was measured; empty if not measured.
std::string numa_toml(const NumaFigures& n);

/// For the user: why nothing was measured, a ratio above 1, a noisy pair, nodes of unequal
/// CPUs, a binding not undone.
std::vector<std::string> numa_notes(const NumaFigures& n);

}  // namespace pagecache::calibrate
