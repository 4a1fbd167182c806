#include "workload/memory_profile.hpp"

#include <pagecache/event.hpp>

#include <algorithm>
#include <cmath>

namespace pagecache::workload {

MemoryProfile::MemoryProfile(Simulator& sim, const std::vector<Host*>& hosts, double interval)
    : sim_(sim), hosts_(hosts), interval_(interval), last_(hosts.size()) {}

void MemoryProfile::start(TraceSink& sink, const int& running) {
  sink_ = &sink;
  if (interval_ > 0.0) {
    sim_.spawn(sample(&running));
    return;
  }
  // A profile of every change is recorded as the changes happen, from now: the files cached
  // at the start changed memory before there was anything to report to.
  for (std::size_t i = 0; i < hosts_.size(); ++i) {
    hosts_[i]->set_memory_observer([this, i](double now, const MemoryState& m) { record(now, i, m); });
  }
  record_all();
}

// A host's row only when its memory differs from its previous row. True if it got one.
bool MemoryProfile::record(double now, std::size_t host, const MemoryState& m) {
  std::optional<MemoryState>& last = last_[host];
  if (last && *last == m) return false;
  last = m;
  sink_->on_memory({.host = static_cast<std::uint32_t>(host), .time = now, .state = m});
  return true;
}

bool MemoryProfile::record_all() {
  bool any = false;
  for (std::size_t i = 0; i < hosts_.size(); ++i) any = record(sim_.now(), i, hosts_[i]->memory()) || any;
  return any;
}

// Until some host's memory changes. The hosts are observed only meanwhile, so that a sampled
// profile does not pay for a call at every change.
Task<void> MemoryProfile::wait_for_change() {
  Event changed(sim_);
  for (Host* host : hosts_) {
    host->set_memory_observer([&changed](double, const MemoryState&) {
      if (!changed.triggered()) changed.trigger();
    });
  }
  co_await changed.wait();
  for (Host* host : hosts_) host->set_memory_observer({});
}

// At every tick of the interval at which some host's memory differs from its previous row.
// Ticks after which nothing changed are skipped, not slept through one by one: the run's
// events follow its work, not its simulated length (a "1e300 s" compute, or a "1 ns" interval
// through an idle stretch, would take one event per tick for ever).
Task<void> MemoryProfile::sample(const int* running) {
  double tick = sim_.now();
  while (*running > 0) {
    if (record_all()) {
      tick += interval_;
    } else {
      // Nothing changed since the last rows: wait for a change, then go back on the cadence
      // at the first tick at or after it, but not this tick, whose rows were due before it.
      co_await wait_for_change();
      tick += std::max(1.0, std::ceil((sim_.now() - tick) / interval_)) * interval_;
    }
    co_await sim_.sleep(tick - sim_.now());
  }
}

}  // namespace pagecache::workload
