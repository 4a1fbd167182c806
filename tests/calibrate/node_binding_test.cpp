// calibrate's SystemNodeBinding, its system calls made for real on this machine's node 0 (every
// machine has one), in a thread of the test's own so that the test process is left as it was.
// (The thread records; the test's thread checks: Catch2 asserts from one thread.)
#include "calibrate/node_binding.hpp"

#include <catch2/catch.hpp>

#include <cerrno>
#include <functional>
#include <string>
#include <thread>

#include <sched.h>

using namespace pagecache::calibrate;

namespace {

// What the thread saw.
struct Seen {
  int cpus = 0;
  int refused = 0;          ///< set_mempolicy's error for node 0 (0: accepted)
  std::string missing;      ///< the error of binding memory to a node no machine has
  std::string no_cpu;       ///< the error of running on CPUs this process may not use
  std::string released;     ///< release()'s report
  bool same_affinity = false;
};

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const BindingError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("calibrate's system binding places a thread and its memory on node 0, and names the call a missing node fails", "[calibrate][numa]") {
  NumaNode node0 = read_numa_topology().nodes.front();
  if (node0.cpus.empty()) node0.cpus = {::sched_getcpu()};  // no node folder: this CPU stands for node 0's
  Seen seen;
  std::jthread([&] {
    cpu_set_t before;
    ::sched_getaffinity(0, sizeof before, &before);
    SystemNodeBinding binding;
    seen.cpus = binding.run_on(node0);
    try {
      binding.allocate_on(node0.id);
      seen.missing = error_of([&] { binding.allocate_on(4000); });  // a node number no machine has online
    } catch (const BindingError& e) {
      seen.refused = e.code().value();
    }
    seen.no_cpu = error_of([&] { binding.run_on(NumaNode{1, {100000}}); });
    seen.released = binding.release();
    cpu_set_t after;
    ::sched_getaffinity(0, sizeof after, &after);
    seen.same_affinity = CPU_EQUAL(&before, &after);
  });
  CHECK(seen.cpus >= 1);
  CHECK(seen.cpus <= static_cast<int>(node0.cpus.size()));
  CHECK_THAT(seen.no_cpu, Catch::Contains("none of node 1's CPUs (100000)"));
  CHECK(seen.same_affinity);
  if (seen.refused != 0) {
    // A container's seccomp profile may forbid set_mempolicy: then release() says so too.
    CHECK(seen.refused == EPERM);
    CHECK_THAT(seen.released, Catch::Contains("set_mempolicy(MPOL_DEFAULT)"));
    WARN("set_mempolicy refused here: its checks skipped");
    return;
  }
  CHECK_THAT(seen.missing, Catch::Contains("set_mempolicy(MPOL_BIND) to node 4000"));
  CHECK(seen.released.empty());
}
