#pragma once
// What the run estimate (estimate/estimate.cpp) counts: the events each operation costs, as the engine
// counts them, and the loads the tasks put on each host and each stream of tasks.

#include <cstddef>
#include <map>
#include <vector>

namespace pagecache::estimate {

// Events per chunk, as the engine counts them: a transfer is a flow, which costs about two
// events (its completion scheduled, its process woken); a latency is a sleep, one more.
constexpr double kFlowEvents = 2.0;
// A chunk read locally: one flow, from the device or from the cache (both when split).
constexpr double kLocalReadEvents = kFlowEvents;
// A chunk written into a writeback cache: the copy, and later the writeback of its block,
// whoever writes it (the writer at the dirty limit, reclaim, background writeback, expiry).
constexpr double kCachedWriteEvents = 2.0 * kFlowEvents;
// A chunk written through to the device (writethrough, O_DIRECT).
constexpr double kDeviceWriteEvents = kFlowEvents;
// A chunk to or from another host: one flow through the route (hits in the client's cache
// are one flow through its memory), after the route's latency.
constexpr double kRemoteEvents = 1.5;
// A workflow task's start: spawned, woken by its prerequisites, given its cores.
constexpr double kWorkflowTaskStartEvents = 3.0;
// A throttled writer pauses 1 s at most (DirtyThrottle::Writer::next).
constexpr double kMaxPause = 1.0;

// What the tasks ask of one host: its devices' bytes, its cores' seconds, and what its page
// cache must hold and write back.
struct HostLoad {
  std::vector<double> disk_read, disk_write;  // bytes per disk, all reads and writes
  std::vector<double> dirtied;                // bytes per disk written into this host's cache (writeback)
  double memory_read = 0.0, memory_write = 0.0;
  double cpu = 0.0;         // core-seconds computed here
  double anonymous = 0.0;   // application memory held at once by the tasks running here
  double writers = 0.0;     // write streams into this host's cache at once
  double dirtied_ops = 0.0; // chunks written into this host's cache
  double write_rounds = 0.0;  // write phases one after another into this cache (the most of any stream)
  double group_pauses = 0.0;  // pauses memory groups' own dirty limits impose
};

// One stream of tasks (an application, or a workflow's tasks that run at once) as it loads the
// hosts: what it writes where, and how many write phases it has there.
struct StreamWrites {
  std::map<std::size_t, double> phases;  // host -> write phases into its cache
  std::map<std::size_t, double> bytes;   // host -> bytes dirtied there
  std::map<std::size_t, double> ops;     // host -> chunks dirtied there
};

}  // namespace pagecache::estimate
