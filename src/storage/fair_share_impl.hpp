#pragma once
// FairShare::Impl: the state behind FairShare, shared by its three parts: fair_share.cpp (flows
// starting and ending, resources crossed alone, the public interface), coupled_flows.cpp
// (flows coupling resources: classes, components, their solution) and hub.cpp (saturated
// resources many classes cross).

#include <pagecache/fair_share.hpp>
#include <pagecache/trace.hpp>

#include "engine/object_pool.hpp"
#include "storage/flow_class.hpp"
#include "storage/flow_state.hpp"
#include "storage/hub.hpp"
#include "storage/max_min.hpp"
#include "storage/processor_sharing.hpp"

#include <deque>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pagecache {

struct FairShare::Impl {
  explicit Impl(Simulator& s) : sim(s) {}

  // One resource and how the rates of the flows crossing it are found. While no multi-resource
  // flow crosses it (`coupled == 0`) its flows are held by `sharing` alone, in O(log n) per
  // change; otherwise they are Explicit, members of the classes listed in `classes`, and
  // solved with the rest of their component. (Listing every flow, needed or not, would cost a
  // cache miss per flow end at 10^5 flows: removing one moves another.)
  struct ResourceState {
    ResourceState(Impl* owner_, std::uint32_t index_, std::string name_, Simulator& sim,
                  EventCallback flow_due, EventCallback head_due)
        : owner(owner_), index(index_), name(std::move(name_)), sharing(sim, flow_due, head_due, this) {}

    Impl* owner;
    std::uint32_t index;
    std::string name;
    std::vector<detail::FlowClass*> classes;  // the classes of Explicit flows crossing it (none while not coupled)
    std::size_t coupled = 0;          // how many flows crossing it cross other resources too
    detail::ProcessorSharing sharing;
    std::uint64_t visit = 0;
    std::uint32_t local = 0;  // index within the component being solved, or kLeftOut
    // While coupled: the capacity its classes used when last solved (sum of cost *
    // contribution), classes gone since included: an upper bound, kept so that capacity freed
    // by a departure does not make a saturated resource look slack before it is solved again.
    // And the change a solve that leaves it out would make to it.
    double usage = 0.0;
    double pending = 0.0;
    // While it is a hub (see Hub); how many Bound classes of a hub cross it; scratch for a
    // satellite's ranges (usage at the hub's level, and its growth with that level).
    std::unique_ptr<detail::Hub> hub;
    std::uint32_t hub_bound = 0;
    double load = 0.0;
    double slope = 0.0;
  };

  // A solve may leave out a resource that is crossed by many classes and not close to
  // saturation (see solve_component). One crossed by a few costs little to keep in, and a
  // class left with nothing limiting it would need a second solve.
  static constexpr std::size_t kLeaveOutAbove = 4;  // classes
  static constexpr double kSlack = 1e-6;            // of its capacity
  static constexpr std::uint32_t kLeftOut = std::numeric_limits<std::uint32_t>::max();
  // A saturated resource crossed by this many classes becomes a hub (below it, solving the
  // whole component costs about as much); a satellite larger than this many classes is
  // solved with its whole component instead.
  static constexpr std::size_t kHubAbove = 32;    // classes
  static constexpr std::size_t kSatelliteAtMost = 64;  // classes

  Simulator& sim;
  std::deque<ResourceState> resources;  // deque: stable addresses
  // A trace consumer, and the start and work of each flow in progress while it listens (kept
  // aside, so that the flows of an untraced run carry nothing for it).
  struct TracedFlow {
    double start;
    double work;
  };
  TraceSink* trace = nullptr;
  std::unordered_map<const detail::FlowState*, TracedFlow> traced;
  void report_flow(const detail::FlowState* flow);
  detail::ObjectPool<detail::FlowState> pool;
  std::unordered_map<detail::FlowClassKey, std::unique_ptr<detail::FlowClass>, detail::FlowClassKeyHash> classes;
  std::uint64_t next_sequence = 0;
  std::uint64_t next_class_serial = 0;
  std::size_t hubs = 0;
  std::uint64_t visit_stamp = 0;
  std::size_t active = 0;

  // Scratch space, kept to avoid allocating per event.
  std::vector<detail::FlowState*> finished;  // by a head or class event, to be woken
  std::vector<ResourceState*> component_resources;
  std::vector<ResourceState*> left_out;
  std::vector<detail::FlowClass*> component_classes;
  std::vector<detail::MaxMinFlow> problem;
  std::vector<double> reserved;
  std::vector<detail::FlowClass*> satellite;
  std::vector<ResourceState*> satellite_resources;
  std::vector<std::pair<std::size_t, std::size_t>> satellite_ends;  // (class end, resource end)
  std::vector<double> satellite_ceilings;
  std::uint32_t hub_resource_index = 0;  // the hub being solved
  detail::MaxMinSolver solver;

  ResourceState& resource(ResourceId id) { return resources[id.index]; }

  static void on_flow_due(void* context);
  static void on_head_due(void* context);
  static void on_class_due(void* context);
  static void on_hub_due(void* context);

  void validate(const FlowSpec& spec) const;
  detail::FlowState* start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter);
  void withdraw(detail::FlowState* flow);
  void join(detail::FlowState* flow, double work);
  void drop_if_empty(detail::FlowClass& c);
  void uncouple(const detail::FlowClassKey& key, std::size_t flows);
  void make_explicit(ResourceState& r);
  void make_shared(ResourceState& r);
  // Gathers into component_classes and component_resources the classes and coupled resources
  // reached from the seed class's resources, each resource's `local` its index there.
  // `admit(r)` decides for each resource met whether it joins (true) or is a border not
  // crossed (false, and then it sets r's `local` itself); the search stops once more than
  // `limit` classes are in.
  template <class Admit>
  void search_component(const detail::FlowClassKey& seed, Admit admit, std::size_t limit = std::numeric_limits<std::size_t>::max()) {
    const std::uint64_t stamp = ++visit_stamp;
    component_resources.clear();
    component_classes.clear();
    const auto reach = [&](ResourceState& r) {
      if (r.coupled == 0 || r.visit == stamp) return;
      r.visit = stamp;
      if (!admit(r)) return;
      r.local = static_cast<std::uint32_t>(component_resources.size());
      component_resources.push_back(&r);
    };
    const auto take = [&](detail::FlowClass& c) {
      if (c.visit == stamp) return;
      c.visit = stamp;
      component_classes.push_back(&c);
      for (std::uint8_t u = 0; u < c.key.usage_count; ++u) reach(resource(c.key.usages[u].resource));
    };
    if (auto it = classes.find(seed); it != classes.end()) take(*it->second);
    for (std::uint8_t i = 0; i < seed.usage_count; ++i) reach(resource(seed.usages[i].resource));
    for (std::size_t next = 0; next < component_resources.size() && component_classes.size() <= limit; ++next) {
      for (detail::FlowClass* c : component_resources[next]->classes) take(*c);
    }
  }
  void solve_from(const detail::FlowClassKey& seed);
  bool solve_component(const detail::FlowClassKey& seed, bool leave_out_slack);
  // solve_component's steps: the component's classes as the solver's problem (false: a class
  // left with nothing to limit it); the left-out resources charged (false: one would
  // saturate); the rates applied; usage recounted; a hub formed where many classes meet.
  bool make_problem();
  bool charge_left_out();
  void apply_rates();
  void recount_usage();
  void form_hub_if_crowded();
  void schedule_head(detail::FlowClass& c);
  void finish_head(detail::FlowClass& c);

  // Hubs (hub.cpp).
  bool solve_at_hub(const detail::FlowClassKey& seed);
  void form_hub(ResourceState& r);
  void dissolve_hubs();
  void dissolve(ResourceState& r);
  void release(detail::FlowClass& c);
  void attach_bound(detail::Hub& hub, detail::FlowClass& c, double ceiling);
  void attach_fixed(detail::Hub& hub, detail::FlowClass& c, double floor, double usage);
  double satellite_ceiling(std::span<detail::FlowClass* const> members, std::span<ResourceState* const> around,
                           std::uint32_t hub_local, double level);
  void apply_satellite(detail::Hub& hub, std::span<detail::FlowClass* const> members, std::span<ResourceState* const> around,
                       std::uint32_t hub_local, double ceiling);
  void schedule_hub(detail::Hub& hub);
  static std::size_t hub_usage_index(const detail::FlowClass& c, std::uint32_t hub_resource);
  void wake(detail::FlowState* flow);
};

}  // namespace pagecache
