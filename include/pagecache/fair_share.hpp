#pragma once
// FairShare: how concurrent transfers share devices (docs/model.md §5).
//
// The vocabulary is SimGrid's. A *resource* (a disk, a memory bus, a network link, a set of
// CPU cores) has a capacity of 1: one second of its time per second. A *flow* is a transfer of
// `work` units (bytes, or core-seconds) through one or more resources; crossing resource r at
// rate x costs `cost_r * x` of r's capacity, where cost_r is the resource time one unit needs
// (1 / bandwidth). The sum of the costs on a resource never exceeds 1.
//
// Rates are the weighted max-min fair allocation (progressive filling): every flow's rate
// grows in proportion to its `weight` until a resource it crosses is saturated or the flow
// reaches its own `bound`; then it is frozen and the others keep growing. Consequences:
//   - n equal flows on one resource each get 1/n of it;
//   - a read and a write on a disk with different read and write bandwidths get the same rate
//     r, with r / read_bw + r / write_bw = 1 (the disk serves both streams in turn);
//   - a flow crossing a disk and a link runs at the rate of the more loaded of the two;
//   - a memory copy is capped by its per-flow bound until the aggregate saturates.
//
// Rates change only when the set of flows on a resource changes; how a change is solved and
// what it costs (processor sharing, classes of flows, hubs) is in docs/model.md §5.

#include <pagecache/simulator.hpp>

#include <array>
#include <coroutine>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace pagecache {

/// Identifies a resource within its FairShare.
struct ResourceId {
  std::uint32_t index = 0;
  friend bool operator==(ResourceId, ResourceId) = default;
};

/// One resource crossed by a flow: `cost` is the resource time (s) one unit of work uses,
/// i.e. 1 / the resource's bandwidth for this kind of flow. Must be > 0.
struct Usage {
  ResourceId resource;
  double cost = 0.0;
};

/// A flow through a route of several network links crosses them all, its ends (a disk, the
/// two hosts' memories) too.
inline constexpr std::size_t kMaxResourcesPerFlow = 8;
inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// What a flow transfers and through what.
struct FlowSpec {
  double work = 0.0;           ///< units to transfer (bytes, core-seconds); >= 0
  double bound = kUnbounded;   ///< maximum rate, units/s; > 0
  double weight = 1.0;         ///< relative share where flows compete; > 0
  std::array<Usage, kMaxResourcesPerFlow> usages{};
  std::size_t usage_count = 0;

  /// Adds a resource crossed by the flow.
  FlowSpec& through(Usage usage);
  FlowSpec& with_bound(double rate);
  FlowSpec& with_weight(double w);
};

class FairShare;
class TraceSink;

namespace detail {
struct FlowState;
}

/// Awaitable flow: `co_await share.transfer(spec)` returns when all the work is through. The
/// flow starts when the awaiter is made, so await it at once (as `co_await` does); it holds
/// no copy of the spec, which keeps the frames of the coroutines that await flows small.
/// Destroying it while the flow runs (its process torn down) withdraws the flow.
class [[nodiscard]] FlowAwaiter {
 public:
  FlowAwaiter(FairShare& share, const FlowSpec& spec);
  FlowAwaiter(const FlowAwaiter&) = delete;
  FlowAwaiter& operator=(const FlowAwaiter&) = delete;
  ~FlowAwaiter();

  bool await_ready() const noexcept { return flow_ == nullptr; }
  void await_suspend(std::coroutine_handle<> waiting) noexcept;
  void await_resume() const noexcept {}

 private:
  friend class FairShare;
  FairShare* share_;
  detail::FlowState* flow_ = nullptr;
};

class FairShare {
 public:
  /// It may outlive `sim` once no flow is in progress: destroying the simulator destroys its
  /// processes, and with them their flows.
  explicit FairShare(Simulator& sim);
  ~FairShare();
  FairShare(const FairShare&) = delete;
  FairShare& operator=(const FairShare&) = delete;

  /// Adds a resource (capacity: one second of its time per second).
  ResourceId add_resource(std::string name);
  const std::string& name(ResourceId resource) const;
  std::size_t resource_count() const noexcept;

  /// A flow to await. Throws SimulationError if the spec is invalid (negative work, a cost or
  /// weight <= 0, no resource and no finite bound, an unknown resource).
  FlowAwaiter transfer(const FlowSpec& spec) { return FlowAwaiter(*this, spec); }

  /// Flows in progress, in total and through one resource.
  std::size_t active_flows() const noexcept;
  std::size_t active_flows(ResourceId resource) const;
  /// Resources solved as hubs right now: saturated, shared by many classes of flows, each
  /// change re-solving one client's part (for tests and benchmarks).
  std::size_t hubs() const noexcept;
  /// Fraction of the resource's time in use right now (sum of cost * rate), in [0, 1].
  double utilization(ResourceId resource) const;

  Simulator& simulator() const noexcept { return *sim_; }

  /// Reports every flow that starts from now on to `sink` when it ends (nullptr: to none).
  void set_trace(TraceSink* sink);

  /// Checks the internal structures (group membership, sums, events) against a recomputation;
  /// throws InvariantError on a mismatch. O(flows); meant for tests.
  void check_invariants() const;

 private:
  friend class FlowAwaiter;
  struct Impl;
  detail::FlowState* start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter);
  void withdraw(detail::FlowState* flow) noexcept;
  void check_hubs() const;

  Simulator* sim_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pagecache
