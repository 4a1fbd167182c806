#pragma once
// FlowState: the fair-share model's record of one flow in progress. Pooled; owned by FairShare.
//
// A flow is in one of three modes:
//  - Sharing: on a resource it crosses alone, not capped by its bound. Its progress is read off
//    the resource's virtual clock: it finishes when the clock reaches `virtual_finish`.
//  - Bounded: on a resource it crosses alone, running at its own bound. Rate is constant until
//    the resource's flow set changes; it has its own completion event.
//  - Explicit: in a component of resources coupled by multi-resource flows, a member of the
//    class of flows interchangeable with it (FlowClass); the class's rate comes from
//    progressive filling over the component, and its progress is read off the class's virtual
//    clock: it finishes when the clock reaches `virtual_finish`.

#include <pagecache/fair_share.hpp>

#include "engine/indexed_heap.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace pagecache::detail {

struct FlowState;
struct FlowClass;

// A flow's place in one of processor sharing's heaps. The key is copied into the heap's array
// so that comparisons do not chase the pointer to the flow (cache misses dominate with many
// flows); the sequence number breaks ties in start order.
struct KeyedFlow {
  double key;
  std::uint64_t sequence;
  FlowState* flow;
};

struct SmallestKeyFirst {
  bool operator()(const KeyedFlow& a, const KeyedFlow& b) const noexcept {
    if (a.key != b.key) return a.key < b.key;
    return a.sequence < b.sequence;
  }
};
struct LargestKeyFirst {
  bool operator()(const KeyedFlow& a, const KeyedFlow& b) const noexcept {
    if (a.key != b.key) return a.key > b.key;
    return a.sequence > b.sequence;
  }
};

// Each heap tells the flow where its entry is, in a field of its own.
template <std::uint32_t FlowState::*Field>
struct PlaceFlow {
  void operator()(const KeyedFlow& entry, std::uint32_t index) const noexcept { entry.flow->*Field = index; }
};

enum class FlowMode : std::uint8_t { Sharing, Bounded, Explicit };

// Laid out for the common case, a flow on one resource in processor sharing: what it touches
// from start to end lies in the first two cache lines; the fields of flows solved explicitly
// (more resources, their class) come after. FairShare initialises a recycled
// flow field by field instead of assigning FlowState(): with 10^5 flows in flight a recycled
// one is out of cache, and the two lines it writes are the ones it uses.
struct alignas(64) FlowState {
  // Line 0: what it is, its progress.
  void* owner = nullptr;  // the FairShare implementation holding it
  double weight = 1.0;
  double bound = kUnbounded;
  double threshold = kUnbounded;  // bound / weight: the fair-share level at which the bound bites
  std::uint64_t sequence = 0;     // start order, breaks ties deterministically
  double remaining = 0.0;         // Bounded: work left at time `updated`
  double rate = 0.0;              // Bounded: current rate
  double updated = 0.0;

  // Line 1: where it is, who waits for it, its first resource.
  double virtual_finish = 0.0;  // Sharing/Explicit: resource or class virtual time at which it is done
  EventHandle completion;       // Bounded
  std::coroutine_handle<> waiting;
  FlowAwaiter* awaiter = nullptr;
  std::uint32_t finish_index = 0;             // in the sharing flows' (or its class's) heap by virtual finish
  std::uint32_t sharing_threshold_index = 0;  // in the sharing flows' heap by threshold
  std::uint32_t bounded_threshold_index = 0;  // in the bounded flows' heap by threshold
  FlowMode mode = FlowMode::Explicit;
  std::uint8_t usage_count = 0;
  std::array<Usage, kMaxResourcesPerFlow> usages{};  // usages[0] ends line 1

  // Explicit flows only.
  FlowClass* flow_class = nullptr;

  double cost() const noexcept { return usages[0].cost; }  // for single-resource flows
  double remaining_at(double now) const noexcept { return remaining - rate * (now - updated); }
};

static_assert(offsetof(FlowState, usages) + sizeof(Usage) <= 128, "a processor-shared flow fits in two cache lines");

using FinishHeap = IndexedHeap<KeyedFlow, SmallestKeyFirst, PlaceFlow<&FlowState::finish_index>>;
using LowestThresholdFirst = IndexedHeap<KeyedFlow, SmallestKeyFirst, PlaceFlow<&FlowState::sharing_threshold_index>>;
using HighestThresholdFirst = IndexedHeap<KeyedFlow, LargestKeyFirst, PlaceFlow<&FlowState::bounded_threshold_index>>;

}  // namespace pagecache::detail
