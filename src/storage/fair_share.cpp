#include <pagecache/fair_share.hpp>

#include "engine/check.hpp"
#include "engine/object_pool.hpp"
#include "storage/flow_class.hpp"
#include "storage/flow_state.hpp"
#include "storage/max_min.hpp"
#include "storage/precision.hpp"
#include "storage/processor_sharing.hpp"

#include <fmt/format.h>

#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>
#include <vector>

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

struct FairShare::Impl {
  explicit Impl(Simulator& s) : sim(s) {}

  // One resource and how the rates of the flows crossing it are found. While no multi-resource
  // flow crosses it (`coupled == 0`) its flows are held by `sharing` alone, in O(log n) per
  // change; otherwise they are Explicit, members of the classes listed in `classes`, and
  // solved with the rest of their component. (Listing every flow, needed or not, was a cache
  // miss per flow end at 10^5 flows: removing one moves another.)
  struct ResourceState {
    ResourceState(Impl* owner_, std::uint32_t index_, std::string name_, Simulator& sim,
                  EventCallback flow_due, EventCallback head_due)
        : owner(owner_), index(index_), name(std::move(name_)), sharing(sim, flow_due, head_due, this) {}

    Impl* owner;
    std::uint32_t index;
    std::string name;
    std::vector<FlowClass*> classes;  // the classes of Explicit flows crossing it (none while not coupled)
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
  };

  // A solve may leave out a resource that is crossed by many classes and not close to
  // saturation (see solve_component). One crossed by a few costs little to keep in, and a
  // class left with nothing limiting it would need a second solve.
  static constexpr std::size_t kLeaveOutAbove = 4;  // classes
  static constexpr double kSlack = 1e-6;            // of its capacity
  static constexpr std::uint32_t kLeftOut = std::numeric_limits<std::uint32_t>::max();

  Simulator& sim;
  std::deque<ResourceState> resources;  // deque: stable addresses
  detail::ObjectPool<FlowState> pool;
  std::unordered_map<FlowClassKey, std::unique_ptr<FlowClass>, detail::FlowClassKeyHash> classes;
  std::uint64_t next_sequence = 0;
  std::uint64_t visit_stamp = 0;
  std::size_t active = 0;

  // Scratch space, kept to avoid allocating per event.
  std::vector<FlowState*> finished;  // by a head or class event, to be woken
  std::vector<ResourceState*> component_resources;
  std::vector<ResourceState*> left_out;
  std::vector<FlowClass*> component_classes;
  std::vector<detail::MaxMinFlow> problem;
  detail::MaxMinSolver solver;

  ResourceState& resource(ResourceId id) { return resources[id.index]; }

  static void on_flow_due(void* context);
  static void on_head_due(void* context);
  static void on_class_due(void* context);

  void validate(const FlowSpec& spec) const;
  FlowState* start(const FlowSpec& spec, std::coroutine_handle<> waiting, FlowAwaiter* awaiter);
  void withdraw(FlowState* flow);
  void join(FlowState* flow, double work);
  void drop_if_empty(FlowClass& c);
  void uncouple(const FlowClassKey& key, std::size_t flows);
  void make_explicit(ResourceState& r);
  void make_shared(ResourceState& r);
  void solve_from(const FlowClassKey& seed);
  bool solve_component(const FlowClassKey& seed, bool leave_out_slack);
  void schedule_head(FlowClass& c);
  void wake(FlowState* flow);
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

void FairShare::Impl::join(FlowState* flow, double work) {
  auto [it, made] = classes.try_emplace(FlowClassKey::of(*flow));
  if (made) {
    it->second = std::make_unique<FlowClass>();
    FlowClass& c = *it->second;
    c.key = it->first;
    c.owner = this;
    c.updated = sim.now();
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
  const std::uint64_t stamp = ++visit_stamp;
  component_resources.clear();
  left_out.clear();
  component_classes.clear();
  const auto reach = [&](ResourceState& r) {
    if (r.coupled == 0 || r.visit == stamp) return;
    r.visit = stamp;
    if (leave_out_slack && r.classes.size() > kLeaveOutAbove && r.usage < 1.0 - kSlack) {
      r.local = kLeftOut;
      r.pending = 0.0;
      left_out.push_back(&r);
      return;
    }
    r.local = static_cast<std::uint32_t>(component_resources.size());
    component_resources.push_back(&r);
  };
  const auto take = [&](FlowClass& c) {
    if (c.visit == stamp) return;
    c.visit = stamp;
    component_classes.push_back(&c);
    for (std::uint8_t u = 0; u < c.key.usage_count; ++u) reach(resource(c.key.usages[u].resource));
  };
  if (auto it = classes.find(seed); it != classes.end()) take(*it->second);
  for (std::uint8_t i = 0; i < seed.usage_count; ++i) reach(resource(seed.usages[i].resource));
  for (std::size_t next = 0; next < component_resources.size(); ++next) {
    for (FlowClass* c : component_resources[next]->classes) take(*c);
  }
  if (component_classes.empty()) return true;

  // A class of n flows is one flow of n times their weight and bound (see FlowClass).
  problem.resize(component_classes.size());
  for (std::size_t i = 0; i < component_classes.size(); ++i) {
    FlowClass& c = *component_classes[i];
    PC_ASSERT(!c.members.empty());
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
  solver.solve(problem, component_resources.size());
  if (!left_out.empty()) {
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
  }
  // A class whose rate and first member are unchanged keeps its event: in a component of many
  // clients of one server, most changes leave most classes as they were.
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
  for (ResourceState* r : component_resources) {
    r->usage = 0.0;
    for (const FlowClass* c : r->classes) {
      for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
        if (c->key.usages[u].resource.index == r->index) r->usage += c->key.usages[u].cost * c->contribution;
      }
    }
  }
  return true;
}

void FairShare::Impl::schedule_head(FlowClass& c) {
  PC_ASSERT(c.rate > 0.0);
  const double due = sim.now() + std::max(0.0, c.members.top().key - c.virtual_time) / c.rate;
  if (c.head_event) sim.reschedule(c.head_event, due);
  else c.head_event = sim.schedule_at(due, &on_class_due, &c);
  c.head_moved = false;
}

void FairShare::Impl::wake(FlowState* flow) {
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

void FairShare::Impl::on_class_due(void* context) {
  auto& c = *static_cast<FlowClass*>(context);
  Impl& self = *static_cast<Impl*>(c.owner);
  c.head_event.reset();  // it is firing now
  c.advance(self.sim.now());
  // The head is due now by construction; pin the clock to it so rounding cannot leave it running.
  c.virtual_time = std::max(c.virtual_time, c.members.top().key);
  std::vector<FlowState*>& done = self.finished;
  done.clear();
  while (!c.members.empty() && c.members.top().key <= c.virtual_time) {
    done.push_back(c.members.top().flow);
    c.members.pop();
  }
  c.head_moved = true;
  const FlowClassKey key = c.key;
  self.drop_if_empty(c);
  self.uncouple(key, done.size());
  self.solve_from(key);
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

std::size_t FairShare::active_flows(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  std::size_t flows = r.sharing.size();
  for (const FlowClass* c : r.classes) flows += c->size();
  return flows;
}

double FairShare::utilization(ResourceId resource) const {
  const auto& r = impl_->resource(resource);
  if (r.coupled == 0) return r.sharing.usage();
  double usage = 0.0;
  for (const FlowClass* c : r.classes) {
    for (std::uint8_t u = 0; u < c->key.usage_count; ++u) {
      if (c->key.usages[u].resource == resource) usage += c->key.usages[u].cost * c->rate * static_cast<double>(c->size());
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
      PC_ASSERT(c.rate > 0.0 && static_cast<bool>(c.head_event));
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
  PC_ASSERT_MSG(flows_seen == impl_->active, fmt::format("{} flows registered, {} active", flows_seen, impl_->active));
  PC_ASSERT(classes_seen == impl_->classes.size());
  PC_ASSERT(impl_->pool.in_use() == impl_->active);
}

}  // namespace pagecache
