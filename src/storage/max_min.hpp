#pragma once
// Weighted max-min fair rates by progressive filling, for flows crossing several resources.
//
// Every resource has capacity 1; flow f uses cost_{f,r} of resource r per unit of rate. All
// unfrozen flows grow together, flow f at weight_f * t. As t rises, the first limit reached
// freezes flows: a resource saturating freezes every unfrozen flow crossing it (at
// weight_f * t), a flow reaching its bound freezes that flow (at bound_f). Frozen flows keep
// their share; the others continue from there. A round costs O(flows * usages + resources);
// after a few rounds the next limits come from a heap of the resources by the level at which
// each saturates and a heap of the flows by bound, so that a solve costs O(flows * usages *
// log(flows + resources)) however many distinct levels there are (clients of one server
// behind links of many speeds make one level per speed).

#include <pagecache/fair_share.hpp>

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
  std::array<std::uint32_t, kMaxResourcesPerFlow> resource{};  // indices in [0, resource_count)
  std::array<double, kMaxResourcesPerFlow> cost{};
  double rate = 0.0;  // output
  double level = 0.0;        // output: the level at which it froze (its rate is min(bound, weight * level))
  std::uint32_t limit = 0;   // output: the resource that froze it, or kByBound
};

/// MaxMinFlow::limit of a flow frozen by its own bound.
inline constexpr std::uint32_t kByBound = 0xffffffffu;

class MaxMinSolver {
 public:
  /// Sets `rate`, `level` and `limit` of every flow. Each flow must cross a resource or have a
  /// finite bound. `reserved`, if given, is capacity of each resource already taken by flows
  /// outside the problem (a share of a saturated server held by clients not being solved).
  void solve(std::span<MaxMinFlow> flows, std::size_t resource_count, std::span<const double> reserved = {});

 private:
  // A limit ahead: a resource's saturation level or a flow's bound / weight. The heaps keep
  // stale entries (a resource's level rises as flows on it freeze elsewhere; a flow may freeze
  // on a resource before its bound), skipped when they come out: with N flows frozen in one
  // round, as when N clients share one saturated server, nothing is re-keyed.
  struct Limit {
    double level;
    std::uint32_t index;  // resource or flow
  };
  struct LaterLimit {
    bool operator()(const Limit& a, const Limit& b) const noexcept {
      return a.level > b.level || (a.level == b.level && a.index > b.index);
    }
  };

  static constexpr int kPlainRounds = 4;

  void solve_with_heaps(std::span<MaxMinFlow> flows, std::size_t resource_count, std::uint32_t unfrozen, double level);
  // solve_with_heaps' steps: the unfrozen flows indexed by resource and both heaps built; the
  // entries that no longer hold dropped; the flows that freeze at `level` (into freezing_);
  // those charged to their resources, whose levels rise. The last returns how many froze.
  void index_unfrozen(std::span<const MaxMinFlow> flows, std::size_t resource_count);
  void prune_heaps();
  void collect_freezing(std::span<MaxMinFlow> flows, double level);
  std::uint32_t charge_freezing(std::span<MaxMinFlow> flows, double level);
  double saturation_level(std::size_t resource) const noexcept;

  void reset_used(std::size_t resource_count);

  std::span<const double> reserved_;
  std::vector<double> used_;                // capacity used by frozen flows (and reserved), per resource
  std::vector<double> demand_;              // sum of cost * weight of unfrozen flows per resource
  std::vector<std::uint32_t> unfrozen_on_;  // unfrozen flows per resource
  std::vector<std::uint32_t> first_flow_;   // per resource: where its flows start in flows_on_
  std::vector<std::uint32_t> flows_on_;
  std::vector<Limit> saturations_;          // heap of resources by saturation level
  std::vector<Limit> bounds_;               // heap of bounded flows by bound / weight
  std::vector<std::uint32_t> freezing_;
  std::vector<std::uint8_t> frozen_;
};

}  // namespace pagecache::detail
