#include "storage/max_min.hpp"

#include "engine/check.hpp"
#include "storage/precision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pagecache::detail {

double MaxMinSolver::saturation_level(std::size_t resource) const noexcept {
  return std::max(0.0, 1.0 - used_[resource]) / demand_[resource];
}

void MaxMinSolver::reset_used(std::size_t resource_count) {
  if (reserved_.empty()) used_.assign(resource_count, 0.0);
  else used_.assign(reserved_.begin(), reserved_.begin() + static_cast<std::ptrdiff_t>(resource_count));
}

void MaxMinSolver::solve(std::span<MaxMinFlow> flows, std::size_t resource_count, std::span<const double> reserved) {
  PC_ASSERT(reserved.empty() || reserved.size() >= resource_count);
  reserved_ = reserved;
  const auto n = static_cast<std::uint32_t>(flows.size());
  frozen_.assign(n, 0);
  std::uint32_t unfrozen = n;
  double level = 0.0;
  // Rounds with every sum taken afresh, O(flows * usages + resources) each: most solves need
  // one to three. Many more levels (clients behind links of many speeds) go on with heaps.
  const double tie = 1.0 + precision::kRelativeRate;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  reset_used(resource_count);
  for (int round = 0; unfrozen > 0 && round < kPlainRounds; ++round) {
    demand_.assign(resource_count, 0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (frozen_[i]) continue;
      const MaxMinFlow& f = flows[i];
      for (std::uint8_t u = 0; u < f.usage_count; ++u) demand_[f.resource[u]] += f.cost[u] * f.weight;
    }
    // The next limit: the lowest level at which a resource saturates or a bound is reached.
    level = kInf;
    for (std::size_t r = 0; r < resource_count; ++r) {
      if (demand_[r] > 0.0) level = std::min(level, saturation_level(r));
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!frozen_[i]) level = std::min(level, flows[i].bound / flows[i].weight);
    }
    PC_ASSERT_MSG(level < kInf, "a flow crosses no resource and has no bound");

    for (std::uint32_t i = 0; i < n; ++i) {
      if (frozen_[i]) continue;
      MaxMinFlow& f = flows[i];
      bool freeze = f.bound / f.weight <= level * tie;
      f.limit = kByBound;
      for (std::uint8_t u = 0; u < f.usage_count && !freeze; ++u) {
        freeze = saturation_level(f.resource[u]) <= level * tie;
        f.limit = f.resource[u];
      }
      if (!freeze) continue;
      f.rate = std::min(f.bound, f.weight * level);
      f.level = level;
      frozen_[i] = 1;
      --unfrozen;
    }
    // Charge the frozen flows to every resource they cross.
    reset_used(resource_count);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!frozen_[i]) continue;
      const MaxMinFlow& f = flows[i];
      for (std::uint8_t u = 0; u < f.usage_count; ++u) used_[f.resource[u]] += f.cost[u] * f.rate;
    }
  }
  if (unfrozen > 0) solve_with_heaps(flows, resource_count, unfrozen, level);
}

// The rest of the solve, the flows not frozen yet, with the next limit taken from a heap of
// the resources by saturation level and a heap of the flows by bound / weight.
void MaxMinSolver::solve_with_heaps(std::span<MaxMinFlow> flows, std::size_t resource_count, std::uint32_t unfrozen,
                                    double level) {
  index_unfrozen(flows, resource_count);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  while (unfrozen > 0) {
    prune_heaps();
    // The next limit: the lowest level at which a resource saturates or a bound is reached.
    double next = saturations_.empty() ? kInf : saturations_.front().level;
    if (!bounds_.empty()) next = std::min(next, bounds_.front().level);
    PC_ASSERT_MSG(next < kInf, "a flow crosses no resource and has no bound");
    level = std::max(level, next);  // levels only rise; rounding must not lower them
    collect_freezing(flows, level);
    unfrozen -= charge_freezing(flows, level);
  }
}

void MaxMinSolver::index_unfrozen(std::span<const MaxMinFlow> flows, std::size_t resource_count) {
  const auto n = static_cast<std::uint32_t>(flows.size());
  demand_.assign(resource_count, 0.0);
  unfrozen_on_.assign(resource_count, 0);
  first_flow_.assign(resource_count + 1, 0);
  saturations_.clear();
  bounds_.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (frozen_[i]) continue;
    const MaxMinFlow& f = flows[i];
    for (std::uint8_t u = 0; u < f.usage_count; ++u) {
      demand_[f.resource[u]] += f.cost[u] * f.weight;
      ++unfrozen_on_[f.resource[u]];
      ++first_flow_[f.resource[u] + 1];
    }
    if (std::isfinite(f.bound)) bounds_.push_back({f.bound / f.weight, i});
  }
  for (std::size_t r = 0; r < resource_count; ++r) first_flow_[r + 1] += first_flow_[r];
  flows_on_.resize(first_flow_[resource_count]);
  freezing_.assign(first_flow_.begin(), first_flow_.end() - 1);  // scratch: next free slot per resource
  for (std::uint32_t i = 0; i < n; ++i) {
    if (frozen_[i]) continue;
    for (std::uint8_t u = 0; u < flows[i].usage_count; ++u) flows_on_[freezing_[flows[i].resource[u]]++] = i;
  }
  for (std::size_t r = 0; r < resource_count; ++r) {
    if (unfrozen_on_[r] > 0) saturations_.push_back({saturation_level(r), static_cast<std::uint32_t>(r)});
  }
  std::make_heap(saturations_.begin(), saturations_.end(), LaterLimit{});
  std::make_heap(bounds_.begin(), bounds_.end(), LaterLimit{});
}

// Drops the entries that no longer hold: frozen flows, resources without unfrozen flows or
// whose level has risen since.
void MaxMinSolver::prune_heaps() {
  const LaterLimit later;
  while (!bounds_.empty() && frozen_[bounds_.front().index]) {
    std::pop_heap(bounds_.begin(), bounds_.end(), later);
    bounds_.pop_back();
  }
  while (!saturations_.empty()) {
    const Limit& top = saturations_.front();
    if (unfrozen_on_[top.index] > 0 && top.level == saturation_level(top.index)) break;
    std::pop_heap(saturations_.begin(), saturations_.end(), later);
    saturations_.pop_back();
  }
}

// Every flow reaching its bound or crossing a resource that saturates at this level.
void MaxMinSolver::collect_freezing(std::span<MaxMinFlow> flows, double level) {
  const LaterLimit later;
  const double tie = 1.0 + precision::kRelativeRate;
  freezing_.clear();
  while (!bounds_.empty() && bounds_.front().level <= level * tie) {
    const std::uint32_t i = bounds_.front().index;
    std::pop_heap(bounds_.begin(), bounds_.end(), later);
    bounds_.pop_back();
    if (frozen_[i]) continue;
    frozen_[i] = 1;
    flows[i].limit = kByBound;
    freezing_.push_back(i);
  }
  for (prune_heaps(); !saturations_.empty() && saturations_.front().level <= level * tie; prune_heaps()) {
    const std::uint32_t r = saturations_.front().index;
    std::pop_heap(saturations_.begin(), saturations_.end(), later);
    saturations_.pop_back();
    for (std::uint32_t k = first_flow_[r]; k < first_flow_[r + 1]; ++k) {
      const std::uint32_t i = flows_on_[k];
      if (frozen_[i]) continue;
      frozen_[i] = 1;
      flows[i].limit = r;
      freezing_.push_back(i);
    }
  }
}

// Charge them to every resource they cross; a resource with flows still unfrozen gets its new
// (higher) level, its old entry going stale (one entry per frozen flow crossing it: equal, and
// the extra ones freeze nothing when they come out).
std::uint32_t MaxMinSolver::charge_freezing(std::span<MaxMinFlow> flows, double level) {
  for (const std::uint32_t i : freezing_) {
    MaxMinFlow& f = flows[i];
    f.rate = std::min(f.bound, f.weight * level);
    f.level = level;
    for (std::uint8_t u = 0; u < f.usage_count; ++u) {
      const std::uint32_t r = f.resource[u];
      used_[r] += f.cost[u] * f.rate;
      demand_[r] -= f.cost[u] * f.weight;
      --unfrozen_on_[r];
    }
  }
  const LaterLimit later;
  for (const std::uint32_t i : freezing_) {
    const MaxMinFlow& f = flows[i];
    for (std::uint8_t u = 0; u < f.usage_count; ++u) {
      const std::uint32_t r = f.resource[u];
      if (unfrozen_on_[r] == 0) continue;
      saturations_.push_back({saturation_level(r), r});
      std::push_heap(saturations_.begin(), saturations_.end(), later);
    }
  }
  return static_cast<std::uint32_t>(freezing_.size());
}

}  // namespace pagecache::detail
