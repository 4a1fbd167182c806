// FairShare's hubs: a saturated resource shared by many classes, solved one satellite at a time
// (see Hub in hub.hpp).

#include "engine/check.hpp"
#include "storage/fair_share_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pagecache {

using detail::FlowClass;
using detail::FlowClassKey;
using detail::Hub;
using detail::HubRole;

std::size_t FairShare::Impl::hub_usage_index(const FlowClass& c, std::uint32_t hub_resource) {
  for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
    if (c.key.usages[u].resource.index == hub_resource) return u;
  }
  return c.key.usage_count;
}

// Takes a class out of its hub. A Bound class keeps the rate it has now, with no event of its
// own yet: whoever releases it solves it or schedules it.
void FairShare::Impl::release(FlowClass& c) {
  if (c.hub_role == HubRole::None) return;
  Hub& h = *static_cast<Hub*>(c.hub);
  const double now = sim.now();
  c.advance(now);  // on the hub's clock or its own rate, before either is left
  if (c.hub_role == HubRole::Bound) {
    c.rate = c.key.weight * h.level;
    c.contribution = c.rate * static_cast<double>(c.size());
    h.heads.erase(c.hub_head_index);
    h.ceilings.erase(c.hub_range_index);
    h.demand -= c.hub_share;
    for (std::uint8_t u = 0; u < c.key.usage_count; ++u) --resource(c.key.usages[u].resource).hub_bound;
  } else {
    h.floors.erase(c.hub_range_index);
    h.fixed -= c.hub_share;
  }
  c.hub_role = HubRole::None;
  c.hub = nullptr;
  if (--h.classes == 0) {
    h.demand = 0.0;  // no rounding left over from the sums
    h.fixed = 0.0;
  }
}

void FairShare::Impl::attach_bound(Hub& h, FlowClass& c, double ceiling) {
  PC_ASSERT(c.hub_role == HubRole::None && !c.members.empty());
  c.advance(h.updated);
  sim.cancel(c.head_event);
  const std::size_t u = hub_usage_index(c, h.resource);
  c.hub_role = HubRole::Bound;
  c.hub = &h;
  c.hub_base_clock = h.clock;
  c.hub_base_time = c.virtual_time;
  c.rate = c.key.weight * h.level;
  c.contribution = c.rate * static_cast<double>(c.size());
  c.hub_share = static_cast<double>(c.size()) * c.key.weight * c.key.usages[u].cost;
  c.head_moved = false;
  h.demand += c.hub_share;
  const double due = h.clock + std::max(0.0, c.members.top().key - c.virtual_time) / c.key.weight;
  h.heads.push({due, c.serial, &c});
  h.ceilings.push({ceiling, c.serial, &c});
  for (std::uint8_t k = 0; k < c.key.usage_count; ++k) ++resource(c.key.usages[k].resource).hub_bound;
  ++h.classes;
}

void FairShare::Impl::attach_fixed(Hub& h, FlowClass& c, double floor, double usage) {
  PC_ASSERT(c.hub_role == HubRole::None);
  c.hub_role = HubRole::Fixed;
  c.hub = &h;
  c.hub_share = usage;
  h.fixed += usage;
  h.floors.push({floor, c.serial, &c});
  ++h.classes;
}

// The highest hub level at which the satellite's solution still holds, or a negative value if
// it holds at `level` alone: a resource it shares with flows the hub bottlenecks is (nearly)
// saturated, so any change of level would move others. Leaves each resource's usage at
// `level` in its `load`. The classes' solution is in `problem`, at each class's `local`.
double FairShare::Impl::satellite_ceiling(std::span<FlowClass* const> members, std::span<ResourceState* const> around,
                                          std::uint32_t hub_local, double level) {
  for (ResourceState* r : around) {
    r->load = 0.0;
    r->slope = 0.0;
  }
  const std::uint32_t hub_index = hub_resource_index;
  double ceiling = std::numeric_limits<double>::infinity();
  for (const FlowClass* c : members) {
    const detail::MaxMinFlow& p = problem[c->local];
    const bool bound = p.limit == hub_local && hub_usage_index(*c, hub_index) < c->key.usage_count;
    if (bound) ceiling = std::min(ceiling, c->key.bound / c->key.weight);
    for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
      ResourceState& r = resource(c->key.usages[u].resource);
      if (r.index == hub_index) continue;
      r.load += c->key.usages[u].cost * p.rate;
      if (bound) r.slope += c->key.usages[u].cost * p.weight;
    }
  }
  for (const ResourceState* r : around) {
    if (r->slope <= 0.0) continue;
    const double headroom = 1.0 - r->load;
    if (headroom <= kSlack) return -1.0;
    ceiling = std::min(ceiling, level + headroom / r->slope);
  }
  return ceiling;
}

// Gives a satellite's classes their solution: the ones the hub bottlenecks join its clock,
// the others get their rates (their events kept where nothing changed), those crossing the hub
// holding a fixed share of it.
void FairShare::Impl::apply_satellite(Hub& h, std::span<FlowClass* const> members, std::span<ResourceState* const> around,
                                      std::uint32_t hub_local, double ceiling) {
  const double now = sim.now();
  for (FlowClass* c : members) {
    const detail::MaxMinFlow& p = problem[c->local];
    const std::size_t u = hub_usage_index(*c, h.resource);
    const bool crosses = u < c->key.usage_count;
    if (crosses && p.limit == hub_local) {
      attach_bound(h, *c, ceiling);
      continue;
    }
    c->contribution = p.rate;
    const double rate = p.rate / static_cast<double>(c->size());
    if (rate != c->rate || c->head_moved || !c->head_event) {
      c->advance(now);
      c->rate = rate;
      schedule_head(*c);
    }
    if (crosses) attach_fixed(h, *c, p.rate / p.weight, c->key.usages[u].cost * p.rate);
  }
  // Resources crossed by flows on the hub's clock: their usage grows with it, up to capacity.
  for (ResourceState* r : around) r->usage = r->hub_bound > 0 ? 1.0 : r->load;
}

void FairShare::Impl::schedule_hub(Hub& h) {
  if (h.heads.empty()) {
    sim.cancel(h.event);
    return;
  }
  PC_ASSERT(h.level > 0.0);
  const double due = sim.now() + std::max(0.0, h.heads.top().key - h.clock) / h.level;
  if (h.event) sim.reschedule(h.event, due);
  else h.event = sim.schedule_at(due, &on_hub_due, &resources[h.resource]);
}

// A change around a hub: solve the satellite it is in, with the hub's other classes as one flow
// (the Bound ones) and a reservation (the Fixed ones). False if the hub cannot take it (no hub
// here, a satellite too large, a new level outside another satellite's range, a hub no longer
// saturated); hubs met are then dissolved and the component is solved whole.
bool FairShare::Impl::solve_at_hub(const FlowClassKey& seed) {
  if (hubs == 0) return false;
  ResourceState* hub_resource = nullptr;
  bool several = false;
  search_component(
      seed,
      [&](ResourceState& r) {
        if (!r.hub) return true;
        several = several || (hub_resource != nullptr && hub_resource != &r);
        hub_resource = &r;
        return false;
      },
      kSatelliteAtMost);
  if (hub_resource == nullptr) return false;  // none met: solve_component dissolves one if it meets it
  if (several || component_classes.size() > kSatelliteAtMost) {
    dissolve_hubs();
    return false;
  }

  Hub& h = *hub_resource->hub;
  const double now = sim.now();
  h.advance(now);
  for (FlowClass* c : component_classes) release(*c);
  const auto hub_local = static_cast<std::uint32_t>(component_resources.size());
  hub_resource_index = hub_resource->index;
  const double others = h.demand;
  problem.resize(component_classes.size() + (others > 0.0 ? 1 : 0));
  for (std::size_t i = 0; i < component_classes.size(); ++i) {
    FlowClass& c = *component_classes[i];
    c.local = static_cast<std::uint32_t>(i);
    const auto n = static_cast<double>(c.size());
    detail::MaxMinFlow& p = problem[i];
    p.weight = n * c.key.weight;
    p.bound = n * c.key.bound;
    p.usage_count = c.key.usage_count;
    for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
      const ResourceState& r = resource(c.key.usages[u].resource);
      p.resource[u] = r.hub ? hub_local : r.local;
      p.cost[u] = c.key.usages[u].cost;
    }
  }
  if (others > 0.0) {
    detail::MaxMinFlow& rest = problem.back();
    rest = detail::MaxMinFlow{};
    rest.weight = others;
    rest.bound = std::numeric_limits<double>::infinity();
    rest.usage_count = 1;
    rest.resource[0] = hub_local;
    rest.cost[0] = 1.0;
  }
  reserved.assign(component_resources.size() + 1, 0.0);
  reserved[hub_local] = h.fixed;
  solver.solve(problem, component_resources.size() + 1, reserved);

  double level = 0.0;
  if (others > 0.0) {
    level = problem.back().level;
  } else {
    for (std::size_t i = 0; i < component_classes.size(); ++i) {
      if (problem[i].limit == hub_local) level = problem[i].level;
    }
  }
  const bool holds = level > 0.0 && (h.ceilings.empty() || level <= h.ceilings.top().key) &&
                     (h.floors.empty() || level >= h.floors.top().key);
  const double ceiling = holds ? satellite_ceiling(component_classes, component_resources, hub_local, level) : -1.0;
  if (ceiling < level) {
    // Released classes keep their rates until the whole component is solved (a new class,
    // with none yet, is the seed's: solved first).
    for (FlowClass* c : component_classes) {
      if (!c->head_event && c->rate > 0.0) schedule_head(*c);
    }
    dissolve_hubs();
    return false;
  }
  h.level = level;
  apply_satellite(h, component_classes, component_resources, hub_local, ceiling);
  schedule_hub(h);
  return true;
}

// After a solve of a whole component: the saturated resource that bottlenecks the most classes,
// if it is crossed by many, becomes a hub, provided every satellite's solution holds around its
// level (`problem` holds the solution, at each class's `local`).
void FairShare::Impl::form_hub(ResourceState& r) {
  PC_ASSERT(!r.hub && r.local != kLeftOut);
  double level = 0.0;
  for (const FlowClass* c : r.classes) {
    if (problem[c->local].limit == r.local) level = problem[c->local].level;
  }
  if (!(level > 0.0)) return;
  hub_resource_index = r.index;
  const std::uint64_t stamp = ++visit_stamp;
  r.visit = stamp;
  satellite.clear();
  satellite_resources.clear();
  satellite_ends.clear();
  satellite_ceilings.clear();
  for (FlowClass* first : r.classes) {
    if (first->visit == stamp) continue;
    const std::size_t class_begin = satellite.size();
    const std::size_t resource_begin = satellite_resources.size();
    const auto take = [&](FlowClass& c) {
      if (c.visit == stamp) return;
      c.visit = stamp;
      satellite.push_back(&c);
      for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
        ResourceState& s = resource(c.key.usages[u].resource);
        if (s.visit == stamp) continue;
        s.visit = stamp;
        satellite_resources.push_back(&s);
      }
    };
    take(*first);
    for (std::size_t next = resource_begin; next < satellite_resources.size(); ++next) {
      for (FlowClass* c : satellite_resources[next]->classes) take(*c);
      if (satellite.size() - class_begin > kSatelliteAtMost) return;
    }
    const std::span<FlowClass* const> members(satellite.data() + class_begin, satellite.size() - class_begin);
    const std::span<ResourceState* const> around(satellite_resources.data() + resource_begin,
                                                 satellite_resources.size() - resource_begin);
    const double ceiling = satellite_ceiling(members, around, r.local, level);
    if (ceiling < level) return;
    satellite_ends.emplace_back(satellite.size(), satellite_resources.size());
    satellite_ceilings.push_back(ceiling);
  }

  r.hub = std::make_unique<Hub>(r.index);
  ++hubs;
  Hub& h = *r.hub;
  h.level = level;
  h.clock = 0.0;
  h.updated = sim.now();
  std::size_t class_begin = 0;
  std::size_t resource_begin = 0;
  for (std::size_t s = 0; s < satellite_ends.size(); ++s) {
    const auto [class_end, resource_end] = satellite_ends[s];
    apply_satellite(h, {satellite.data() + class_begin, class_end - class_begin},
                    {satellite_resources.data() + resource_begin, resource_end - resource_begin}, r.local, satellite_ceilings[s]);
    class_begin = class_end;
    resource_begin = resource_end;
  }
  r.usage = 1.0;
  schedule_hub(h);
}

void FairShare::Impl::dissolve(ResourceState& r) {
  Hub& h = *r.hub;
  h.advance(sim.now());
  while (!h.heads.empty()) {
    FlowClass& c = *h.heads.top().flow_class;
    release(c);
    schedule_head(c);
  }
  while (!h.floors.empty()) release(*h.floors.top().flow_class);
  sim.cancel(h.event);
  r.hub.reset();
  --hubs;
}

void FairShare::Impl::dissolve_hubs() {
  for (ResourceState& r : resources) {
    if (hubs == 0) break;
    if (r.hub) dissolve(r);
  }
}

void FairShare::Impl::on_hub_due(void* context) {
  auto& r = *static_cast<ResourceState*>(context);
  Impl& self = *r.owner;
  Hub& h = *r.hub;
  h.event.reset();  // it is firing now
  PC_ASSERT(!h.heads.empty());
  h.advance(self.sim.now());
  FlowClass& c = *h.heads.top().flow_class;
  self.release(c);  // advances it on the hub's clock
  self.finish_head(c);
}

}  // namespace pagecache
