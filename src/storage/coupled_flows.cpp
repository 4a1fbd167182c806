// FairShare's flows that cross several resources: the classes of interchangeable flows, the
// components of resources they couple, and the max-min solution of a component when a flow of
// it starts or ends (see FlowClass, and FairShare::Impl::solve_component).

#include "engine/check.hpp"
#include "storage/fair_share_impl.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace pagecache {

using detail::FlowClass;
using detail::FlowClassKey;
using detail::FlowMode;
using detail::FlowState;

void FairShare::Impl::join(FlowState* flow, double work) {
  auto [it, made] = classes.try_emplace(FlowClassKey::of(*flow));
  if (made) {
    it->second = std::make_unique<FlowClass>();
    FlowClass& c = *it->second;
    c.key = it->first;
    c.owner = this;
    c.updated = sim.now();
    c.serial = next_class_serial++;
    for (std::uint8_t i = 0; i < c.key.usage_count; ++i) {
      ResourceState& r = resource(c.key.usages[i].resource);
      c.slots[i] = static_cast<std::uint32_t>(r.classes.size());
      r.classes.push_back(&c);
    }
  }
  FlowClass& c = *it->second;
  c.advance(sim.now());
  flow->mode = FlowMode::Explicit;
  flow->flow_class = &c;
  flow->virtual_finish = c.virtual_time + std::max(work, 0.0);
  c.members.push({flow->virtual_finish, flow->sequence, flow});
  c.head_moved = true;
}

void FairShare::Impl::drop_if_empty(FlowClass& c) {
  if (!c.members.empty()) return;
  release(c);
  sim.cancel(c.head_event);
  for (std::uint8_t i = 0; i < c.key.usage_count; ++i) {
    ResourceState& r = resource(c.key.usages[i].resource);
    const std::uint32_t slot = c.slots[i];
    FlowClass* moved = r.classes.back();
    r.classes[slot] = moved;
    r.classes.pop_back();
    if (moved != &c) {
      for (std::uint8_t j = 0; j < moved->key.usage_count; ++j) {
        if (moved->key.usages[j].resource.index == r.index) moved->slots[j] = slot;
      }
    }
  }
  const FlowClassKey key = c.key;  // erasing destroys c
  classes.erase(key);
}

// `flows` of class `key` have ended: the resources they crossed may no longer be coupled.
void FairShare::Impl::uncouple(const FlowClassKey& key, std::size_t flows) {
  for (std::uint8_t i = 0; i < key.usage_count; ++i) {
    ResourceState& r = resource(key.usages[i].resource);
    if (key.usage_count > 1) r.coupled -= flows;
    if (r.coupled == 0 && !r.classes.empty()) make_shared(r);
  }
}

void FairShare::Impl::make_explicit(ResourceState& r) {
  r.sharing.drain([this](FlowState* flow, double remaining) { join(flow, remaining); });
  r.usage = 1.0;  // not known until it is solved: never left out before
  r.pending = 0.0;
}

void FairShare::Impl::make_shared(ResourceState& r) {
  // Every flow left here crosses r alone; hand them back to processor sharing in start order.
  if (r.hub) dissolve(r);
  const double now = sim.now();
  std::vector<std::pair<FlowState*, double>> flows;
  while (!r.classes.empty()) {
    FlowClass& c = *r.classes.back();
    PC_ASSERT(c.key.usage_count == 1);
    c.advance(now);
    for (const detail::KeyedFlow& entry : c.members) {
      entry.flow->flow_class = nullptr;
      flows.emplace_back(entry.flow, std::max(0.0, entry.key - c.virtual_time));
    }
    c.members.clear();
    drop_if_empty(c);
  }
  std::sort(flows.begin(), flows.end(), [](const auto& a, const auto& b) { return a.first->sequence < b.first->sequence; });
  for (auto& [flow, remaining] : flows) r.sharing.add(flow, remaining);
}

void FairShare::Impl::solve_from(const FlowClassKey& seed) {
  if (solve_at_hub(seed)) return;
  if (!solve_component(seed, true)) solve_component(seed, false);
}

// Solves the component around the seed class's resources, or, with `leave_out_slack`, the part
// of it reached without crossing resources that are crossed by many classes and stay
// unsaturated. Leaving those out is exact: in a max-min allocation a resource below capacity
// is no flow's bottleneck, so its constraint can be dropped without changing the allocation,
// as long as it is still below capacity afterwards (checked; false if not, or if a class is
// left with nothing to limit it, and then nothing is changed). With N clients of one server
// that is not saturated, a change on one client solves that client's classes, not N.
bool FairShare::Impl::solve_component(const FlowClassKey& seed, bool leave_out_slack) {
  left_out.clear();
  bool met_hub = false;
  search_component(seed, [&](ResourceState& r) {
    met_hub = met_hub || r.hub != nullptr;
    if (leave_out_slack && r.classes.size() > kLeaveOutAbove && r.usage < 1.0 - kSlack && r.hub_bound == 0) {
      r.local = kLeftOut;
      r.pending = 0.0;
      left_out.push_back(&r);
      return false;
    }
    return true;
  });
  if (met_hub) {
    // A hub solves its satellites alone; the whole component is solved without it.
    dissolve_hubs();
    return solve_component(seed, leave_out_slack);
  }
  if (component_classes.empty()) return true;
  if (!make_problem()) return false;
  solver.solve(problem, component_resources.size());
  if (!left_out.empty() && !charge_left_out()) return false;
  apply_rates();
  recount_usage();
  if (left_out.empty() && component_classes.size() > kHubAbove) form_hub_if_crowded();
  return true;
}

// A class of n flows is one flow of n times their weight and bound (see FlowClass).
bool FairShare::Impl::make_problem() {
  problem.resize(component_classes.size());
  for (std::size_t i = 0; i < component_classes.size(); ++i) {
    FlowClass& c = *component_classes[i];
    PC_ASSERT(!c.members.empty());
    c.local = static_cast<std::uint32_t>(i);
    const auto n = static_cast<double>(c.size());
    detail::MaxMinFlow& p = problem[i];
    p.weight = n * c.key.weight;
    p.bound = n * c.key.bound;
    p.usage_count = 0;
    for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
      const std::uint32_t local = resource(c.key.usages[u].resource).local;
      if (local == kLeftOut) continue;
      p.resource[p.usage_count] = local;
      p.cost[p.usage_count] = c.key.usages[u].cost;
      ++p.usage_count;
    }
    if (p.usage_count == 0 && !std::isfinite(p.bound)) return false;
  }
  return true;
}

bool FairShare::Impl::charge_left_out() {
  for (std::size_t i = 0; i < component_classes.size(); ++i) {
    const FlowClass& c = *component_classes[i];
    const double change = problem[i].rate - c.contribution;
    for (std::uint8_t u = 0; u < c.key.usage_count; ++u) {
      ResourceState& r = resource(c.key.usages[u].resource);
      if (r.local == kLeftOut) r.pending += c.key.usages[u].cost * change;
    }
  }
  for (const ResourceState* r : left_out) {
    if (r->usage + r->pending >= 1.0 - kSlack) return false;
  }
  for (ResourceState* r : left_out) r->usage += r->pending;
  return true;
}

// A class whose rate and first member are unchanged keeps its event: in a component of many
// clients of one server, most changes leave most classes as they were.
void FairShare::Impl::apply_rates() {
  const double now = sim.now();
  for (std::size_t i = 0; i < component_classes.size(); ++i) {
    FlowClass& c = *component_classes[i];
    c.contribution = problem[i].rate;
    const double rate = problem[i].rate / static_cast<double>(c.size());
    if (rate == c.rate && !c.head_moved && c.head_event) continue;
    c.advance(now);
    c.rate = rate;
    schedule_head(c);
  }
}

void FairShare::Impl::recount_usage() {
  for (ResourceState* r : component_resources) {
    r->usage = 0.0;
    for (const FlowClass* c : r->classes) {
      for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
        if (c->key.usages[u].resource.index == r->index) r->usage += c->key.usages[u].cost * c->contribution;
      }
    }
  }
}

// The resource bottlenecking the most classes, if many cross it: a hub from now on.
void FairShare::Impl::form_hub_if_crowded() {
  ResourceState* busiest = nullptr;
  for (ResourceState* r : component_resources) r->slope = 0.0;
  for (const detail::MaxMinFlow& p : problem) {
    if (p.limit != detail::kByBound) component_resources[p.limit]->slope += 1.0;
  }
  for (ResourceState* r : component_resources) {
    if (r->classes.size() > kHubAbove && r->slope > 0.0 && (busiest == nullptr || r->slope > busiest->slope)) busiest = r;
  }
  if (busiest != nullptr) form_hub(*busiest);
}

void FairShare::Impl::schedule_head(FlowClass& c) {
  PC_ASSERT(c.rate > 0.0);
  const double due = sim.now() + std::max(0.0, c.members.top().key - c.virtual_time) / c.rate;
  if (c.head_event) sim.reschedule(c.head_event, due);
  else c.head_event = sim.schedule_at(due, &on_class_due, &c);
  c.head_moved = false;
}

void FairShare::Impl::on_class_due(void* context) {
  auto& c = *static_cast<FlowClass*>(context);
  Impl& self = *static_cast<Impl*>(c.owner);
  c.head_event.reset();  // it is firing now
  c.advance(self.sim.now());
  self.finish_head(c);
}

// The first member of `c`, its clock advanced to now, is due: it and every member done with it
// end, the component is solved again, and their processes wake.
void FairShare::Impl::finish_head(FlowClass& c) {
  // The head is due now by construction; pin the clock to it so rounding cannot leave it running.
  c.virtual_time = std::max(c.virtual_time, c.members.top().key);
  std::vector<FlowState*>& done = finished;
  done.clear();
  while (!c.members.empty() && c.members.top().key <= c.virtual_time) {
    done.push_back(c.members.top().flow);
    c.members.pop();
  }
  c.head_moved = true;
  const FlowClassKey key = c.key;
  drop_if_empty(c);
  uncouple(key, done.size());
  solve_from(key);
  for (FlowState* flow : done) wake(flow);
}

}  // namespace pagecache
