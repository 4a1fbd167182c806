#pragma once
// FlowClass: the flows of a component of coupled resources that cross the same resources at
// the same costs, with the same bound and weight.
//
// The max-min allocation is unique and such flows are interchangeable in it, so they all get
// one rate. Progressive filling can therefore solve a class as a single flow of the members'
// summed weight and bound, and the class advances its members the way processor sharing does:
// one virtual clock counting the work each member has done, a heap of the members' virtual
// finishes, and one event in the simulator's queue, for the first of them. Starting or
// finishing a flow re-solves the component's classes, not its flows: N applications reading
// over NFS through one client make a handful of classes however large N is.

#include "storage/flow_state.hpp"

#include <pagecache/fair_share.hpp>
#include <pagecache/simulator.hpp>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

namespace pagecache::detail {

/// What makes flows interchangeable. Unused usages stay zero, so that == compares them too.
struct FlowClassKey {
  std::array<Usage, kMaxResourcesPerFlow> usages{};
  std::uint8_t usage_count = 0;
  double bound = kUnbounded;
  double weight = 1.0;

  static FlowClassKey of(const FlowState& flow) noexcept {
    FlowClassKey key;
    key.usage_count = flow.usage_count;
    for (std::uint8_t u = 0; u < flow.usage_count; ++u) key.usages[u] = flow.usages[u];
    key.bound = flow.bound;
    key.weight = flow.weight;
    return key;
  }

  friend bool operator==(const FlowClassKey& a, const FlowClassKey& b) noexcept {
    if (a.usage_count != b.usage_count || a.bound != b.bound || a.weight != b.weight) return false;
    for (std::uint8_t u = 0; u < a.usage_count; ++u) {
      if (a.usages[u].resource != b.usages[u].resource || a.usages[u].cost != b.usages[u].cost) return false;
    }
    return true;
  }
};

struct FlowClassKeyHash {
  std::size_t operator()(const FlowClassKey& key) const noexcept {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ key.usage_count;
    const auto mix = [&h](std::uint64_t v) { h = (h ^ v) * 0x100000001b3ULL; h ^= h >> 29; };
    for (std::uint8_t u = 0; u < key.usage_count; ++u) {
      mix(key.usages[u].resource.index);
      mix(std::bit_cast<std::uint64_t>(key.usages[u].cost));
    }
    mix(std::bit_cast<std::uint64_t>(key.bound));
    mix(std::bit_cast<std::uint64_t>(key.weight));
    return static_cast<std::size_t>(h);
  }
};

// The progress clock of a saturated server's flows (see Hub): `clock` is the integral of
// `level`, the rate per unit weight of every flow the server bottlenecks, up to `updated`.
struct HubClock {
  double level = 0.0;
  double clock = 0.0;
  double updated = 0.0;
  double at(double now) const noexcept { return clock + level * (now - updated); }
};

// A class's part in a hub: bottlenecked by it (its progress is the hub's clock), crossing it
// bottlenecked elsewhere, or neither.
enum class HubRole : std::uint8_t { None, Bound, Fixed };

// Laid out for the component search and solve, which visit every class of a component at
// every change: what they read comes first.
struct FlowClass {
  std::uint64_t visit = 0;     // component search stamp
  std::uint32_t local = 0;     // index in the component being solved
  bool head_moved = false;     // members joined or left since the head event was scheduled
  double rate = 0.0;           // of each member
  double contribution = 0.0;   // the members' summed rate when last solved, in the resources' usage
  double virtual_time = 0.0;   // work each member has done since the class formed, at `updated`
  double updated = 0.0;
  EventHandle head_event;      // when the first member is done
  FlowClassKey key;
  FinishHeap members;          // by virtual finish, then start order
  void* owner = nullptr;       // the FairShare implementation holding it
  std::array<std::uint32_t, kMaxResourcesPerFlow> slots{};  // index in each resource's class list
  std::uint64_t serial = 0;    // creation order: ties in a hub's heaps

  // In a hub (see Hub): the hub, the class's role, and for a Bound class the hub clock and
  // its own virtual time when it joined; `hub_share` is what it added to the hub's demand
  // (Bound) or fixed usage (Fixed); indices in the hub's heaps.
  HubRole hub_role = HubRole::None;
  HubClock* hub = nullptr;
  double hub_base_clock = 0.0;
  double hub_base_time = 0.0;
  double hub_share = 0.0;
  std::uint32_t hub_head_index = 0;
  std::uint32_t hub_range_index = 0;

  std::size_t size() const noexcept { return members.size(); }
  /// Each member's rate now (a Bound class's follows its hub's level).
  double member_rate() const noexcept { return hub_role == HubRole::Bound ? key.weight * hub->level : rate; }
  void advance(double now) noexcept {
    if (hub_role == HubRole::Bound) {
      virtual_time = hub_base_time + key.weight * (hub->at(now) - hub_base_clock);
    } else if (!members.empty() && now > updated) {
      virtual_time += rate * (now - updated);
    }
    updated = now;
  }
};

}  // namespace pagecache::detail
