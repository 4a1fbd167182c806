#pragma once
// Hub: a saturated resource shared by many classes of flows (the disk of an NFS server with
// thousands of clients), solved incrementally.
//
// Take the hub out of its component and what is left falls apart into satellites: each
// client's link and memory with the classes crossing them. Progressive filling couples the
// satellites only through the hub's level λ (the rate per unit weight of the flows it
// bottlenecks). So the hub keeps λ, the classes it bottlenecks (Bound) progress on one clock,
// the integral of λ, and the others crossing it (Fixed, bottlenecked in their satellite) hold
// a fixed share. A change in one satellite re-solves that satellite with the rest of the hub
// folded into one flow (the Bound classes' summed demand) and the Fixed classes' usage
// reserved: O(satellite) plus O(log N) for the hub's heaps and its one event.
//
// Each satellite's solution holds over a range of λ: up to the level at which a resource of
// it crossed by a Bound class saturates or such a class reaches its bound (its ceiling), and
// down to the highest level of its Fixed classes crossing the hub (their floor: below it they
// would be bottlenecked by the hub). A new λ outside some satellite's range, or a hub no
// longer saturated, dissolves the hub, and the whole component is solved again.

#include "engine/indexed_heap.hpp"
#include "storage/flow_class.hpp"

#include <pagecache/simulator.hpp>

#include <cstddef>
#include <cstdint>

namespace pagecache::detail {

struct HubEntry {
  double key;
  std::uint64_t serial;
  FlowClass* flow_class;
};

struct EarlierHubEntry {
  bool operator()(const HubEntry& a, const HubEntry& b) const noexcept {
    if (a.key != b.key) return a.key < b.key;
    return a.serial < b.serial;
  }
};
struct LaterHubEntry {
  bool operator()(const HubEntry& a, const HubEntry& b) const noexcept {
    if (a.key != b.key) return a.key > b.key;
    return a.serial > b.serial;
  }
};
template <std::uint32_t FlowClass::*Field>
struct PlaceHubEntry {
  void operator()(const HubEntry& entry, std::uint32_t index) const noexcept { entry.flow_class->*Field = index; }
};

struct Hub : HubClock {
  explicit Hub(std::uint32_t resource_index) : resource(resource_index) {}

  std::uint32_t resource;       // its index in FairShare
  double demand = 0.0;          // sum over Bound classes of members * weight * cost here
  double fixed = 0.0;           // capacity taken by Fixed classes
  std::size_t classes = 0;      // Bound and Fixed
  // Bound classes by the hub clock at which their first member is done, and by ceiling;
  // Fixed classes by floor, highest first.
  IndexedHeap<HubEntry, EarlierHubEntry, PlaceHubEntry<&FlowClass::hub_head_index>> heads;
  IndexedHeap<HubEntry, EarlierHubEntry, PlaceHubEntry<&FlowClass::hub_range_index>> ceilings;
  IndexedHeap<HubEntry, LaterHubEntry, PlaceHubEntry<&FlowClass::hub_range_index>> floors;
  EventHandle event;            // when heads' first is due

  void advance(double now) noexcept {
    clock = at(now);
    updated = now;
  }
};

}  // namespace pagecache::detail
