// Progressive filling on small networks whose max-min rates are derived by hand.
#include "storage/max_min.hpp"

#include <catch2/catch.hpp>

#include <limits>
#include <vector>

using pagecache::detail::MaxMinFlow;
using pagecache::detail::MaxMinSolver;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

MaxMinFlow flow(std::initializer_list<std::pair<std::uint32_t, double>> usages, double bound = kInf, double weight = 1.0) {
  MaxMinFlow f;
  f.bound = bound;
  f.weight = weight;
  for (const auto& [r, c] : usages) {
    f.resource[f.usage_count] = r;
    f.cost[f.usage_count] = c;
    ++f.usage_count;
  }
  return f;
}
}  // namespace

TEST_CASE("max-min on a two-link line gives every flow half a link", "[max_min]") {
  // Flow 0 crosses links A and B, flow 1 only A, flow 2 only B; all costs 1. Every flow grows
  // to 0.5, where both links saturate.
  std::vector<MaxMinFlow> flows{flow({{0, 1.0}, {1, 1.0}}), flow({{0, 1.0}}), flow({{1, 1.0}})};
  MaxMinSolver().solve(flows, 2);
  for (const auto& f : flows) CHECK(f.rate == Catch::Detail::Approx(0.5));
}

TEST_CASE("max-min freezes the most loaded link first and gives the rest to the others", "[max_min]") {
  // Link B is twice as costly (cost 2). B carries flows 0 and 2: 2t + 2t = 1 at t = 0.25.
  // Link A then has 1 - 0.25 left for flow 1: 0.75.
  std::vector<MaxMinFlow> flows{flow({{0, 1.0}, {1, 2.0}}), flow({{0, 1.0}}), flow({{1, 2.0}})};
  MaxMinSolver().solve(flows, 2);
  CHECK(flows[0].rate == Catch::Detail::Approx(0.25));
  CHECK(flows[1].rate == Catch::Detail::Approx(0.75));
  CHECK(flows[2].rate == Catch::Detail::Approx(0.25));
}

TEST_CASE("max-min respects per-flow bounds and weights", "[max_min]") {
  // One resource, cost 1. Flow 0 bounded at 0.1; flows 1 and 2 weights 1 and 3 share the
  // remaining 0.9 as t and 3t: t = 0.225.
  std::vector<MaxMinFlow> flows{flow({{0, 1.0}}, 0.1), flow({{0, 1.0}}), flow({{0, 1.0}}, kInf, 3.0)};
  MaxMinSolver().solve(flows, 1);
  CHECK(flows[0].rate == Catch::Detail::Approx(0.1));
  CHECK(flows[1].rate == Catch::Detail::Approx(0.225));
  CHECK(flows[2].rate == Catch::Detail::Approx(0.675));
}

TEST_CASE("max-min leaves a resource unsaturated when every flow is at its bound", "[max_min]") {
  std::vector<MaxMinFlow> flows{flow({{0, 1.0}}, 0.2), flow({{0, 1.0}}, 0.3)};
  MaxMinSolver().solve(flows, 1);
  CHECK(flows[0].rate == Catch::Detail::Approx(0.2));
  CHECK(flows[1].rate == Catch::Detail::Approx(0.3));
}
