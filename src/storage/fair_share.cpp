// FairShare: flows starting and ending, the resources they cross alone (processor sharing),
// and the public interface. Flows coupling resources are solved in coupled_flows.cpp.

#include <pagecache/fair_share.hpp>

#include "engine/check.hpp"
#include "storage/fair_share_impl.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pagecache {

using detail::FlowClass;
using detail::FlowClassKey;
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
  // Every field of the first two lines is set here (see FlowState); usages past usage_count
  // and flow_class (set by join) are never read stale.
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
  if (trace != nullptr) [[unlikely]] traced[flow] = {sim.now(), spec.work};

  ResourceState& first = resource(flow->usages[0].resource);
  if (spec.usage_count == 1 && first.coupled == 0) {
    first.sharing.add(flow, spec.work);
    return flow;
  }
  if (spec.usage_count > 1) {
    for (std::size_t i = 0; i < spec.usage_count; ++i) {
      ResourceState& r = resource(flow->usages[i].resource);
      if (r.coupled++ == 0) make_explicit(r);
    }
  }
  join(flow, spec.work);
  solve_from(flow->flow_class->key);
  return flow;
}

void FairShare::Impl::report_flow(const FlowState* flow) {
  const auto it = traced.find(flow);
  if (it == traced.end()) return;  // started before the consumer listened
  std::array<std::string_view, kMaxResourcesPerFlow> names;
  for (std::size_t i = 0; i < flow->usage_count; ++i) names[i] = resources[flow->usages[i].resource.index].name;
  trace->on_flow({.start = it->second.start, .end = sim.now(), .work = it->second.work, .resources = {names.data(), flow->usage_count}});
  traced.erase(it);
}

void FairShare::Impl::wake(FlowState* flow) {
  if (trace != nullptr) [[unlikely]] report_flow(flow);
  --active;
  flow->awaiter->flow_ = nullptr;
  sim.wake(flow->waiting);
  pool.give_back(flow);
}

// A flow withdrawn before it is done (its process torn down).
void FairShare::Impl::withdraw(FlowState* flow) {
  if (flow->mode != FlowMode::Explicit) {
    resource(flow->usages[0].resource).sharing.remove(flow);
  } else {
    FlowClass& c = *flow->flow_class;
    c.advance(sim.now());
    c.members.erase(flow->finish_index);
    c.head_moved = true;
    const FlowClassKey key = c.key;
    drop_if_empty(c);
    uncouple(key, 1);
    solve_from(key);
  }
  if (trace != nullptr) [[unlikely]] traced.erase(flow);
  --active;
  pool.give_back(flow);
}

void FairShare::Impl::on_flow_due(void* context) {
  auto* flow = static_cast<FlowState*>(context);
  flow->completion.reset();
  auto& self = *static_cast<Impl*>(flow->owner);
  self.resource(flow->usages[0].resource).sharing.remove(flow);
  self.wake(flow);
}

void FairShare::Impl::on_head_due(void* context) {
  auto* r = static_cast<ResourceState*>(context);
  Impl& self = *r->owner;
  std::vector<FlowState*>& done = self.finished;
  done.clear();
  r->sharing.take_finished(done);
  for (FlowState* flow : done) self.wake(flow);
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
    if (r.hub) sim_->cancel(r.hub->event);
    for (FlowClass* c : r.classes) {
      sim_->cancel(c->head_event);
      for (const detail::KeyedFlow& entry : c->members) detach(entry.flow);
    }
    if (!r.sharing.empty()) r.sharing.drain([&](FlowState* flow, double) { detach(flow); });
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

std::size_t FairShare::hubs() const noexcept { return impl_->hubs; }

std::size_t FairShare::active_flows(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  std::size_t flows = r.sharing.size();
  for (const FlowClass* c : r.classes) flows += c->size();
  return flows;
}

void FairShare::set_trace(TraceSink* sink) {
  impl_->trace = sink;
  impl_->traced.clear();
}

double FairShare::utilization(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  if (r.coupled == 0) return r.sharing.usage();
  double usage = 0.0;
  for (const FlowClass* c : r.classes) {
    for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
      if (c->key.usages[u].resource == resource) usage += c->key.usages[u].cost * c->member_rate() * static_cast<double>(c->size());
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
    impl_->withdraw(flow);
  } catch (...) {
  }
}

void FairShare::check_invariants() const {
  std::size_t flows_seen = 0;  // each flow counted once, on its first resource
  std::size_t classes_seen = 0;  // each class counted once, on its first resource
  for (const auto& r : impl_->resources) {
    std::size_t coupled = 0;
    for (std::size_t slot = 0; slot < r.classes.size(); ++slot) {
      const FlowClass& c = *r.classes[slot];
      bool found = false;
      for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
        if (c.key.usages[u].resource.index == r.index) found = c.slots[u] == slot;
      }
      PC_ASSERT_MSG(found, fmt::format("class registry of '{}' out of step", r.name));
      PC_ASSERT(!c.members.empty() && c.members.ordered());
      const bool on_hub_clock = c.hub_role == detail::HubRole::Bound;
      PC_ASSERT(c.rate > 0.0 && static_cast<bool>(c.head_event) != on_hub_clock);
      if (c.hub_role != detail::HubRole::None) {
        const auto* hub = static_cast<const detail::Hub*>(c.hub);
        PC_ASSERT_MSG(Impl::hub_usage_index(c, hub->resource) < c.key.usage_count, fmt::format("a class of '{}' is in a hub it does not cross", r.name));
      }
      const auto it = impl_->classes.find(c.key);
      PC_ASSERT_MSG(it != impl_->classes.end() && it->second.get() == &c, fmt::format("a class of '{}' is not registered", r.name));
      for (const detail::KeyedFlow& entry : c.members) {
        const FlowState& flow = *entry.flow;
        PC_ASSERT(flow.mode == FlowMode::Explicit && flow.flow_class == &c);
        PC_ASSERT(entry.key == flow.virtual_finish);
        PC_ASSERT_MSG(detail::FlowClassKey::of(flow) == c.key, fmt::format("a flow of '{}' is in another's class", r.name));
      }
      if (c.key.usage_count > 1) coupled += c.size();
      if (c.key.usages[0].resource.index == r.index) {
        flows_seen += c.size();
        ++classes_seen;
      }
    }
    PC_ASSERT_MSG(coupled == r.coupled, fmt::format("coupled count of '{}'", r.name));
    if (r.coupled > 0) {
      double usage = 0.0;
      for (const FlowClass* c : r.classes) {
        if (c->hub_role == detail::HubRole::Bound) continue;  // its usage follows the hub's level
        const double total = c->rate * static_cast<double>(c->size());
        PC_ASSERT_MSG(std::abs(c->contribution - total) <= 1e-9 * total, fmt::format("a class of '{}' is not solved", r.name));
        for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
          if (c->key.usages[u].resource.index == r.index) usage += c->key.usages[u].cost * c->contribution;
        }
      }
      PC_ASSERT_MSG(usage <= r.usage + 1e-9, fmt::format("usage of '{}': {} kept, {} summed", r.name, r.usage, usage));
    }
    if (r.coupled == 0) {
      PC_ASSERT_MSG(r.classes.empty(), fmt::format("'{}' lists flows while not coupled", r.name));
      flows_seen += r.sharing.size();
      r.sharing.check();
    } else {
      PC_ASSERT(r.sharing.empty());
    }
    PC_ASSERT_MSG(utilization(ResourceId{r.index}) <= 1.0 + 1e-9, fmt::format("'{}' over capacity", r.name));
  }
  check_hubs();
  PC_ASSERT_MSG(flows_seen == impl_->active, fmt::format("{} flows registered, {} active", flows_seen, impl_->active));
  PC_ASSERT(classes_seen == impl_->classes.size());
  PC_ASSERT(impl_->pool.in_use() == impl_->active);
}

}  // namespace pagecache

namespace pagecache {

// Each hub: its heaps and sums against its classes, its level within every satellite's range,
// and its capacity used in full.
void FairShare::check_hubs() const {
  std::size_t hubs = 0;
  std::vector<std::uint32_t> bound_on(impl_->resources.size(), 0);
  for (const auto& r : impl_->resources) {
    if (!r.hub) continue;
    ++hubs;
    const detail::Hub& h = *r.hub;
    PC_ASSERT_MSG(h.classes == h.heads.size() + h.floors.size() && h.heads.size() == h.ceilings.size(),
                  fmt::format("hub '{}' lists {} classes", r.name, h.classes));
    PC_ASSERT(h.heads.ordered() && h.ceilings.ordered() && h.floors.ordered());
    PC_ASSERT_MSG(h.level > 0.0 && static_cast<bool>(h.event) == !h.heads.empty(), fmt::format("hub '{}' has no level or event", r.name));
    double demand = 0.0;
    for (std::uint32_t i = 0; i < h.heads.size(); ++i) {
      const detail::HubEntry& entry = h.heads.at(i);
      const FlowClass& c = *entry.flow_class;
      PC_ASSERT(c.hub_role == detail::HubRole::Bound && c.hub == &h && c.hub_head_index == i);
      const double due = c.hub_base_clock + std::max(0.0, c.members.top().key - c.hub_base_time) / c.key.weight;
      PC_ASSERT_MSG(entry.key == due, fmt::format("a class of hub '{}' is due at the wrong clock", r.name));
      PC_ASSERT(h.ceilings.at(c.hub_range_index).flow_class == &c);
      demand += c.hub_share;
      for (std::uint8_t u = 0; u < c.key.usage_count; ++u) ++bound_on[c.key.usages[u].resource.index];
    }
    double fixed = 0.0;
    for (std::uint32_t i = 0; i < h.floors.size(); ++i) {
      const FlowClass& c = *h.floors.at(i).flow_class;
      PC_ASSERT(c.hub_role == detail::HubRole::Fixed && c.hub == &h && c.hub_range_index == i);
      fixed += c.hub_share;
    }
    PC_ASSERT_MSG(std::abs(demand - h.demand) <= 1e-9 * demand && std::abs(fixed - h.fixed) <= 1e-9 + 1e-9 * fixed,
                  fmt::format("sums of hub '{}' out of step", r.name));
    PC_ASSERT_MSG((h.ceilings.empty() || h.level <= h.ceilings.top().key) && (h.floors.empty() || h.level >= h.floors.top().key),
                  fmt::format("hub '{}' level {} outside a satellite's range", r.name, h.level));
    if (!h.heads.empty()) {
      const double used = utilization(ResourceId{r.index});
      PC_ASSERT_MSG(std::abs(used - 1.0) <= 1e-6, fmt::format("hub '{}' not saturated: {}", r.name, used));
    }
  }
  PC_ASSERT(hubs == impl_->hubs);
  // Every class's rate is the max-min one, solved afresh over all coupled resources.
  std::vector<detail::MaxMinFlow> problem;
  std::vector<const FlowClass*> order;
  for (const auto& [key, c] : impl_->classes) {
    detail::MaxMinFlow p;
    p.weight = static_cast<double>(c->size()) * key.weight;
    p.bound = static_cast<double>(c->size()) * key.bound;
    p.usage_count = key.usage_count;
    for (std::uint8_t u = 0; u < key.usage_count; ++u) {
      p.resource[u] = key.usages[u].resource.index;
      p.cost[u] = key.usages[u].cost;
    }
    problem.push_back(p);
    order.push_back(c.get());
  }
  detail::MaxMinSolver().solve(problem, impl_->resources.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const double rate = order[i]->member_rate() * static_cast<double>(order[i]->size());
    PC_ASSERT_MSG(std::abs(rate - problem[i].rate) <= 1e-9 * problem[i].rate,
                  fmt::format("a class of {} flows runs at {}, max-min says {} (role {})", order[i]->size(), rate, problem[i].rate,
                              static_cast<int>(order[i]->hub_role)));
  }
  for (const auto& r : impl_->resources) {
    PC_ASSERT_MSG(bound_on[r.index] == r.hub_bound, fmt::format("'{}' counts {} classes on a hub's clock, {} found", r.name, r.hub_bound, bound_on[r.index]));
  }
}

}  // namespace pagecache
