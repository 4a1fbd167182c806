#pragma once
// Test helper: start awaitables at given times and record when each completes.

#include <pagecache/fair_share.hpp>
#include <pagecache/simulator.hpp>

#include <vector>

namespace pagecache::testing {

inline Task<void> flow_at(Simulator& sim, FairShare& share, double start, FlowSpec spec, double& finished) {
  co_await sim.sleep_until(start);
  co_await share.transfer(spec);
  finished = sim.now();
}

inline FlowSpec bytes_through(double work, Usage usage) { return FlowSpec{.work = work}.through(usage); }

}  // namespace pagecache::testing
