#include "storage/max_min.hpp"

#include "engine/check.hpp"
#include "storage/precision.hpp"

#include <algorithm>
#include <limits>

namespace pagecache::detail {

void MaxMinSolver::solve(std::span<MaxMinFlow> flows, std::size_t resource_count) {
  capacity_.assign(resource_count, 1.0);
  frozen_.assign(flows.size(), 0);
  std::size_t unfrozen = flows.size();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double tie = 1.0 + precision::kRelativeRate;

  while (unfrozen > 0) {
    demand_.assign(resource_count, 0.0);
    for (std::size_t i = 0; i < flows.size(); ++i) {
      if (frozen_[i]) continue;
      const MaxMinFlow& f = flows[i];
      for (std::uint8_t u = 0; u < f.usage_count; ++u) demand_[f.resource[u]] += f.cost[u] * f.weight;
    }
    // The next limit: the lowest level at which a resource saturates or a bound is reached.
    double level = kInf;
    for (std::size_t r = 0; r < resource_count; ++r) {
      if (demand_[r] > 0.0) level = std::min(level, capacity_[r] / demand_[r]);
    }
    for (std::size_t i = 0; i < flows.size(); ++i) {
      if (!frozen_[i]) level = std::min(level, flows[i].bound / flows[i].weight);
    }
    PC_ASSERT_MSG(level < kInf, "a flow crosses no resource and has no bound");

    for (std::size_t i = 0; i < flows.size(); ++i) {
      if (frozen_[i]) continue;
      MaxMinFlow& f = flows[i];
      bool freeze = f.bound / f.weight <= level * tie;
      for (std::uint8_t u = 0; u < f.usage_count && !freeze; ++u) {
        const std::uint32_t r = f.resource[u];
        freeze = capacity_[r] / demand_[r] <= level * tie;
      }
      if (!freeze) continue;
      f.rate = std::min(f.bound, f.weight * level);
      frozen_[i] = 1;
      --unfrozen;
    }
    // Charge the newly frozen flows to every resource they cross.
    for (std::size_t r = 0; r < resource_count; ++r) capacity_[r] = 1.0;
    for (std::size_t i = 0; i < flows.size(); ++i) {
      if (!frozen_[i]) continue;
      const MaxMinFlow& f = flows[i];
      for (std::uint8_t u = 0; u < f.usage_count; ++u) capacity_[f.resource[u]] -= f.cost[u] * f.rate;
    }
    for (double& c : capacity_) c = std::max(c, 0.0);
  }
}

}  // namespace pagecache::detail
