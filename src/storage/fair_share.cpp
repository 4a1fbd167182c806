#include <pagecache/fair_share.hpp>

#include "engine/check.hpp"
#include "engine/object_pool.hpp"
#include "storage/flow_state.hpp"
#include "storage/max_min.hpp"
#include "storage/precision.hpp"
#include "storage/processor_sharing.hpp"

#include <fmt/format.h>

#include <cmath>
#include <deque>
#include <vector>

namespace pagecache {

using detail::FlowMode;
using detail::FlowState;

FlowSpec& FlowSpec::through(Usage usage) {
  if (usage_count == kMaxResourcesPerFlow) {
    throw SimulationError(fmt::format("a flow crosses at most {} resources", kMaxResourcesPerFlow));
  }
  usages[usage_count++] = usage;
  return *this;
}

FlowSpec& FlowSpec::with_bound(double rate) {
  bound = rate;
  return *this;
}

FlowSpec& FlowSpec::with_weight(double w) {
  weight = w;
  return *this;
}

struct FairShare::Impl {
  explicit Impl(Simulator& s) : sim(s) {}

  // One resource and how the rates of the flows crossing it are found. While no multi-resource
  // flow crosses it (`coupled == 0`) its flows are held by `sharing` alone, in O(log n) per
  // change; otherwise they are Explicit, listed in `flows`, and solved with the rest of their
  // component. (Listing every flow, needed or not, was a cache miss per flow end at 10^5
  // flows: removing one moves another.)
  struct ResourceState {
    ResourceState(Impl* owner_, std::uint32_t index_, std::string name_, Simulator& sim,
                  EventCallback flow_due, EventCallback head_due)
        : owner(owner_), index(index_), name(std::move(name_)), sharing(sim, flow_due, head_due, this) {}

    Impl* owner;
    std::uint32_t index;
    std::string name;
    std::vector<FlowState*> flows;  // the Explicit flows crossing it (none while not coupled)
    std::size_t coupled = 0;        // how many of them cross other resources too
    detail::ProcessorSharing sharing;
    std::uint64_t visit = 0;
    std::uint32_t local = 0;  // index within the component being solved
  };


  Simulator& sim;
  std::deque<ResourceState> resources;  // deque: stable addresses
  detail::ObjectPool<FlowState> pool;
  std::uint64_t next_sequence = 0;
  std::uint64_t visit_stamp = 0;
  std::size_t active = 0;

  // Scratch space, kept to avoid allocating per event.
  std::vector<FlowState*> finished;
  std::vector<ResourceState*> component_resources;
  std::vector<FlowState*> component_flows;
  std::vector<detail::MaxMinFlow> problem;
  detail::MaxMinSolver solver;

  ResourceState& resource(ResourceId id) { return resources[id.index]; }

  static void on_flow_due(void* context);
  static void on_head_due(void* context);

  void validate(const FlowSpec& spec) const;
  FlowState* start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter);
  void finish(FlowState* flow, bool completed);
  void enlist(FlowState* flow);
  void unregister(FlowState* flow);
  void make_explicit(ResourceState& r);
  void make_shared(ResourceState& r);
  void solve_from(const FlowState& seed);
  void schedule_completion(FlowState* flow);
  void complete(FlowState* flow);
};

void FairShare::Impl::validate(const FlowSpec& spec) const {
  const auto bad = [](const std::string& what) { throw SimulationError("invalid flow: " + what); };
  if (!(spec.work >= 0.0) || !std::isfinite(spec.work)) bad(fmt::format("work {} must be finite and >= 0", spec.work));
  if (!(spec.bound > 0.0)) bad(fmt::format("bound {} must be > 0", spec.bound));
  if (!(spec.weight > 0.0) || !std::isfinite(spec.weight)) bad(fmt::format("weight {} must be finite and > 0", spec.weight));
  if (spec.usage_count == 0) bad("it crosses no resource");
  for (std::size_t i = 0; i < spec.usage_count; ++i) {
    const Usage& u = spec.usages[i];
    if (u.resource.index >= resources.size()) bad(fmt::format("unknown resource #{}", u.resource.index));
    if (!(u.cost > 0.0) || !std::isfinite(u.cost)) {
      bad(fmt::format("cost {} on resource '{}' must be finite and > 0", u.cost, resources[u.resource.index].name));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (spec.usages[j].resource == u.resource) {
        bad(fmt::format("resource '{}' listed twice", resources[u.resource.index].name));
      }
    }
  }
}

FlowState* FairShare::Impl::start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter) {
  validate(spec);
  // Every field of the first two lines is set here (see FlowState); usages past usage_count,
  // slots (set by enlist) and visit (compared with a stamp that only grows) are never read
  // stale.
  FlowState* flow = pool.take_as_left();
  flow->owner = this;
  flow->weight = spec.weight;
  flow->bound = spec.bound;
  flow->threshold = spec.bound / spec.weight;
  flow->sequence = next_sequence++;
  flow->remaining = 0.0;
  flow->rate = 0.0;
  flow->updated = 0.0;
  flow->virtual_finish = 0.0;
  flow->completion = EventHandle();
  flow->waiting = waiting;
  flow->awaiter = awaiter;
  flow->finish_index = 0;
  flow->sharing_threshold_index = 0;
  flow->bounded_threshold_index = 0;
  flow->mode = FlowMode::Explicit;
  flow->usage_count = static_cast<std::uint8_t>(spec.usage_count);
  std::copy_n(spec.usages.begin(), spec.usage_count, flow->usages.begin());
  ++active;

  ResourceState& first = resource(flow->usages[0].resource);
  if (spec.usage_count == 1 && first.coupled == 0) {
    first.sharing.add(flow, spec.work);
    return flow;
  }
  flow->mode = FlowMode::Explicit;
  flow->remaining = spec.work;
  flow->rate = 0.0;
  flow->updated = sim.now();
  if (spec.usage_count > 1) {
    for (std::size_t i = 0; i < spec.usage_count; ++i) {
      ResourceState& r = resource(flow->usages[i].resource);
      if (r.coupled++ == 0) make_explicit(r);
    }
  }
  enlist(flow);
  solve_from(*flow);
  return flow;
}

void FairShare::Impl::enlist(FlowState* flow) {
  for (std::uint8_t i = 0; i < flow->usage_count; ++i) {
    ResourceState& r = resource(flow->usages[i].resource);
    flow->slots[i] = static_cast<std::uint32_t>(r.flows.size());
    r.flows.push_back(flow);
  }
}

void FairShare::Impl::make_explicit(ResourceState& r) {
  const double now = sim.now();
  r.sharing.drain([this, now](FlowState* flow, double remaining) {
    flow->mode = FlowMode::Explicit;
    flow->remaining = remaining;
    flow->rate = 0.0;
    flow->updated = now;
    enlist(flow);
  });
}

void FairShare::Impl::make_shared(ResourceState& r) {
  // Every flow left here crosses r alone; hand them back to processor sharing in start order.
  std::vector<FlowState*> flows = std::move(r.flows);
  r.flows.clear();
  std::sort(flows.begin(), flows.end(), [](const FlowState* a, const FlowState* b) { return a->sequence < b->sequence; });
  const double now = sim.now();
  for (FlowState* flow : flows) {
    PC_ASSERT(flow->mode == FlowMode::Explicit && flow->usage_count == 1);
    sim.cancel(flow->completion);
    const double remaining = flow->remaining_at(now);
    flow->rate = 0.0;
    r.sharing.add(flow, remaining);
  }
}

void FairShare::Impl::solve_from(const FlowState& seed) {
  // Collect the connected component(s) of explicit resources around the seed's resources.
  const std::uint64_t stamp = ++visit_stamp;
  component_resources.clear();
  component_flows.clear();
  for (std::uint8_t i = 0; i < seed.usage_count; ++i) {
    ResourceState& r = resource(seed.usages[i].resource);
    if (r.coupled > 0 && r.visit != stamp) {
      r.visit = stamp;
      component_resources.push_back(&r);
    }
  }
  for (std::size_t next = 0; next < component_resources.size(); ++next) {
    ResourceState& r = *component_resources[next];
    r.local = static_cast<std::uint32_t>(next);
    for (FlowState* flow : r.flows) {
      if (flow->visit == stamp) continue;
      flow->visit = stamp;
      component_flows.push_back(flow);
      for (std::uint8_t u = 0; u < flow->usage_count; ++u) {
        ResourceState& other = resource(flow->usages[u].resource);
        if (other.visit != stamp) {
          other.visit = stamp;
          component_resources.push_back(&other);
        }
      }
    }
  }
  if (component_flows.empty()) return;

  const double now = sim.now();
  problem.resize(component_flows.size());
  for (std::size_t i = 0; i < component_flows.size(); ++i) {
    FlowState* flow = component_flows[i];
    PC_ASSERT(flow->mode == FlowMode::Explicit);
    flow->remaining = flow->remaining_at(now);
    flow->updated = now;
    detail::MaxMinFlow& p = problem[i];
    p.weight = flow->weight;
    p.bound = flow->bound;
    p.usage_count = flow->usage_count;
    for (std::uint8_t u = 0; u < flow->usage_count; ++u) {
      p.resource[u] = resource(flow->usages[u].resource).local;
      p.cost[u] = flow->usages[u].cost;
    }
  }
  solver.solve(problem, component_resources.size());
  for (std::size_t i = 0; i < component_flows.size(); ++i) {
    component_flows[i]->rate = problem[i].rate;
    schedule_completion(component_flows[i]);
  }
}

void FairShare::Impl::schedule_completion(FlowState* flow) {
  PC_ASSERT(flow->rate > 0.0);
  const double due = sim.now() + std::max(0.0, flow->remaining) / flow->rate;
  if (flow->completion) sim.reschedule(flow->completion, due);
  else flow->completion = sim.schedule_at(due, &on_flow_due, flow);
}

void FairShare::Impl::unregister(FlowState* flow) {
  for (std::uint8_t i = 0; i < flow->usage_count; ++i) {
    ResourceState& r = resource(flow->usages[i].resource);
    const std::uint32_t slot = flow->slots[i];
    FlowState* moved = r.flows.back();
    r.flows[slot] = moved;
    r.flows.pop_back();
    if (moved != flow) {
      for (std::uint8_t j = 0; j < moved->usage_count; ++j) {
        if (moved->usages[j].resource.index == r.index) moved->slots[j] = slot;
      }
    }
  }
}

void FairShare::Impl::finish(FlowState* flow, bool completed) {
  if (flow->mode != FlowMode::Explicit) {
    resource(flow->usages[0].resource).sharing.remove(flow);
  } else {
    unregister(flow);
    sim.cancel(flow->completion);
    const bool multi = flow->usage_count > 1;
    for (std::uint8_t i = 0; i < flow->usage_count; ++i) {
      ResourceState& r = resource(flow->usages[i].resource);
      if (multi) --r.coupled;
      if (r.coupled == 0 && !r.flows.empty()) make_shared(r);
    }
    solve_from(*flow);
  }
  --active;
  if (completed) {
    flow->awaiter->flow_ = nullptr;
    sim.wake(flow->waiting);
  }
  pool.give_back(flow);
}

void FairShare::Impl::on_flow_due(void* context) {
  auto* flow = static_cast<FlowState*>(context);
  flow->completion.reset();
  static_cast<Impl*>(flow->owner)->finish(flow, true);
}

void FairShare::Impl::on_head_due(void* context) {
  auto* r = static_cast<ResourceState*>(context);
  Impl& self = *r->owner;
  std::vector<FlowState*>& done = self.finished;
  done.clear();
  r->sharing.take_finished(done);
  for (FlowState* flow : done) {
    --self.active;
    flow->awaiter->flow_ = nullptr;
    self.sim.wake(flow->waiting);
    self.pool.give_back(flow);
  }
}

// --- FlowAwaiter ------------------------------------------------------------------------------

FlowAwaiter::FlowAwaiter(FairShare& share, const FlowSpec& spec) : share_(&share) {
  // No work: nothing to start, the awaiter is ready (a flow may not cross zero resources,
  // but zero bytes of a valid spec are no transfer at all).
  if (spec.work == 0.0) return;
  flow_ = share.start(spec, {}, this);
}

FlowAwaiter::~FlowAwaiter() {
  if (flow_ != nullptr && share_ != nullptr) share_->withdraw(flow_);
}

void FlowAwaiter::await_suspend(std::coroutine_handle<> waiting) noexcept { flow_->waiting = waiting; }

// --- FairShare --------------------------------------------------------------------------------

FairShare::FairShare(Simulator& sim) : sim_(&sim), impl_(std::make_unique<Impl>(sim)) {}

FairShare::~FairShare() {
  // Flows still running belong to processes that will never resume (the simulation is being
  // torn down): detach their awaiters and cancel their events.
  const auto detach = [this](FlowState* flow) {
    if (flow->awaiter != nullptr) {
      flow->awaiter->share_ = nullptr;
      flow->awaiter->flow_ = nullptr;
      flow->awaiter = nullptr;
    }
    sim_->cancel(flow->completion);
  };
  for (auto& r : impl_->resources) {
    for (FlowState* flow : r.flows) detach(flow);
    r.sharing.drain([&](FlowState* flow, double) { detach(flow); });
  }
}

ResourceId FairShare::add_resource(std::string name) {
  const auto index = static_cast<std::uint32_t>(impl_->resources.size());
  impl_->resources.emplace_back(impl_.get(), index, std::move(name), *sim_, &Impl::on_flow_due, &Impl::on_head_due);
  return ResourceId{index};
}

const std::string& FairShare::name(ResourceId resource) const { return impl_->resource(resource).name; }

std::size_t FairShare::resource_count() const noexcept { return impl_->resources.size(); }

std::size_t FairShare::active_flows() const noexcept { return impl_->active; }

std::size_t FairShare::active_flows(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  return r.flows.size() + r.sharing.size();
}

double FairShare::utilization(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  if (r.coupled == 0) return r.sharing.usage();
  double usage = 0.0;
  for (const FlowState* flow : r.flows) {
    for (std::uint8_t u = 0; u < flow->usage_count; ++u) {
      if (flow->usages[u].resource == resource) usage += flow->usages[u].cost * flow->rate;
    }
  }
  return usage;
}

detail::FlowState* FairShare::start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter) {
  return impl_->start(spec, waiting, awaiter);
}

void FairShare::withdraw(detail::FlowState* flow) noexcept {
  // Runs from an awaiter's destructor during teardown: nothing sensible to do with an error.
  try {
    impl_->finish(flow, false);
  } catch (...) {
  }
}

void FairShare::check_invariants() const {
  std::size_t flows_seen = 0;  // each flow counted once, on its first resource
  for (const auto& r : impl_->resources) {
    std::size_t coupled = 0;
    for (std::size_t slot = 0; slot < r.flows.size(); ++slot) {
      const FlowState* flow = r.flows[slot];
      bool found = false;
      for (std::uint8_t u = 0; u < flow->usage_count; ++u) {
        if (flow->usages[u].resource.index == r.index) found = flow->slots[u] == slot;
      }
      PC_ASSERT_MSG(found, fmt::format("flow registry of '{}' out of step", r.name));
      if (flow->usage_count > 1) ++coupled;
      if (flow->usages[0].resource.index == r.index) ++flows_seen;
      PC_ASSERT(flow->mode == FlowMode::Explicit);
      PC_ASSERT(flow->rate > 0.0 && static_cast<bool>(flow->completion));
    }
    PC_ASSERT_MSG(coupled == r.coupled, fmt::format("coupled count of '{}'", r.name));
    if (r.coupled == 0) {
      PC_ASSERT_MSG(r.flows.empty(), fmt::format("'{}' lists flows while not coupled", r.name));
      flows_seen += r.sharing.size();
      r.sharing.check();
    } else {
      PC_ASSERT(r.sharing.empty());
    }
    PC_ASSERT_MSG(utilization(ResourceId{r.index}) <= 1.0 + 1e-9, fmt::format("'{}' over capacity", r.name));
  }
  PC_ASSERT_MSG(flows_seen == impl_->active, fmt::format("{} flows registered, {} active", flows_seen, impl_->active));
  PC_ASSERT(impl_->pool.in_use() == impl_->active);
}

}  // namespace pagecache
