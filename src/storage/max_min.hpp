#pragma once
// Weighted max-min fair rates by progressive filling, for flows crossing several resources.
//
// Every resource has capacity 1; flow f uses cost_{f,r} of resource r per unit of rate. All
// unfrozen flows grow together, flow f at weight_f * t. As t rises, the first limit reached
// freezes flows: a resource saturating freezes every unfrozen flow crossing it (at
// weight_f * t), a flow reaching its bound freezes that flow (at bound_f). Frozen flows keep
// their share; the others continue from there. O(rounds * (flows * usages + resources)).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pagecache::detail {

struct MaxMinFlow {
  double weight = 1.0;
  double bound = 0.0;  // may be infinite
  std::uint8_t usage_count = 0;
  std::array<std::uint32_t, 4> resource{};  // indices in [0, resource_count)
  std::array<double, 4> cost{};
  double rate = 0.0;  // output
};

class MaxMinSolver {
 public:
  /// Sets `rate` of every flow. Each flow must cross a resource or have a finite bound.
  void solve(std::span<MaxMinFlow> flows, std::size_t resource_count);

 private:
  std::vector<double> capacity_;   // capacity left per resource
  std::vector<double> demand_;     // sum of cost * weight of unfrozen flows per resource
  std::vector<std::uint8_t> frozen_;
};

}  // namespace pagecache::detail
