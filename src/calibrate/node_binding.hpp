#pragma once
// NodeBinding: where the calling thread runs and where its new memory comes from, one NUMA node
// each, for calibrate's remote/local measurements. Threads it starts afterwards inherit both
// (the kernel copies CPU affinity and memory policy to a new thread), so a measurement's own
// threads run where it was placed. SystemNodeBinding makes the system calls (no libnuma);
// tests give a fake that records what it is asked.

#include "calibrate/numa_topology.hpp"

#include <string>
#include <system_error>
#include <vector>

namespace pagecache::calibrate {

/// A system call that places a thread or its memory failed; the message names the call and node.
struct BindingError : std::system_error {
  BindingError(int error, const std::string& what) : std::system_error(error, std::generic_category(), what) {}
};

class NodeBinding {
 public:
  virtual ~NodeBinding() = default;
  /// Runs the calling thread on `node`'s CPUs alone; returns how many of them it may use.
  /// Throws BindingError.
  virtual int run_on(const NumaNode& node) = 0;
  /// Takes the calling thread's new memory (pages first touched, page cache it fills) from
  /// `node` alone. Throws BindingError.
  virtual void allocate_on(int node) = 0;
  /// The thread back where it was before run_on, its memory from any node (the default
  /// policy); what failed, or empty. Never throws: it also runs while an error unwinds.
  virtual std::string release() noexcept = 0;
};

/// sched_setaffinity and set_mempolicy(MPOL_BIND) on the calling thread, through their
/// system calls.
class SystemNodeBinding final : public NodeBinding {
 public:
  int run_on(const NumaNode& node) override;
  void allocate_on(int node) override;
  std::string release() noexcept override;

 private:
  std::vector<unsigned long> saved_;  ///< the affinity before the first run_on (empty: none yet)
};

}  // namespace pagecache::calibrate
