// SampleOrder and its generator: the same seed gives the same orders, on any compiler (the
// outputs are pinned to SplitMix64's published reference values); an epoch without replacement
// visits each file once; the bounded draw is unbiased.

#include "workload/sample_order.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace pagecache::workload {
namespace {

std::vector<std::uint32_t> epoch(SampleOrder& order, std::uint64_t count) {
  order.start_epoch();
  std::vector<std::uint32_t> files;
  for (std::uint64_t i = 0; i < count; ++i) files.push_back(order.next());
  return files;
}

TEST_CASE("SplitMix64 gives the reference generator's outputs", "[workload][sample_order]") {
  // Vigna's splitmix64.c from state 0 (the values every port checks against).
  SplitMix64 bits(0);
  CHECK(bits.next() == 0xe220a8397b1dcdafULL);
  CHECK(bits.next() == 0x6e789e6aa1b965f4ULL);
  CHECK(bits.next() == 0x06c45d188009454fULL);
}

TEST_CASE("a bounded draw takes every value below its bound equally often", "[workload][sample_order]") {
  // 6 values, 600,000 draws: 100,000 expected each, a standard deviation of about 289. A biased
  // draw (modulo of 32 bits by 6 errs by 2^-30 only) would pass too; what this catches is a
  // draw out of range or a wrong mapping, e.g. the low half of the product taken.
  SplitMix64 bits(7);
  std::map<std::uint32_t, int> seen;
  for (int i = 0; i < 600'000; ++i) ++seen[bits.below(6)];
  REQUIRE(seen.size() == 6);
  for (const auto& [value, times] : seen) {
    CHECK(value < 6);
    CHECK(times > 100'000 - 5 * 289);
    CHECK(times < 100'000 + 5 * 289);
  }
  // A bound of one is always 0; the largest bound reaches high values.
  CHECK(bits.below(1) == 0);
  std::uint32_t most = 0;
  for (int i = 0; i < 100; ++i) most = std::max(most, bits.below(UINT32_MAX));
  CHECK(most > UINT32_MAX / 2);
}

TEST_CASE("the rejection sliver of a bound is redrawn, not folded in", "[workload][sample_order]") {
  // Bound 3 * 2^30: the high half of x * bound is floor(3x / 4) for a 32-bit x, which maps two
  // draws to every value divisible by 3 and one to the others. Unless the sliver (2^32 mod bound
  // = 2^30 draws) is redrawn, half of the values are divisible by 3 instead of a third.
  const std::uint32_t bound = 3U << 30;
  SplitMix64 bits(11);
  int residues[3] = {0, 0, 0};
  for (int i = 0; i < 300'000; ++i) ++residues[bits.below(bound) % 3];
  for (const int r : residues) {  // 100,000 expected each, a standard deviation of about 258
    CHECK(r > 100'000 - 5 * 258);
    CHECK(r < 100'000 + 5 * 258);
  }
}

TEST_CASE("without replacement, an epoch visits every file once, and the next epoch is another shuffle", "[workload][sample_order]") {
  SampleOrder order(1000, SampleOrder::Kind::Shuffled, 42);
  const std::vector<std::uint32_t> first = epoch(order, 1000);
  const std::vector<std::uint32_t> second = epoch(order, 1000);
  for (const auto& e : {first, second}) {
    std::vector<std::uint32_t> sorted = e;
    std::sort(sorted.begin(), sorted.end());
    for (std::uint32_t i = 0; i < 1000; ++i) REQUIRE(sorted[i] == i);
  }
  CHECK(first != second);
  // Not the identity either: a shuffle of 1000 leaves about one file in place.
  int in_place = 0;
  for (std::uint32_t i = 0; i < 1000; ++i) in_place += first[i] == i ? 1 : 0;
  CHECK(in_place < 10);
}

TEST_CASE("a partial epoch without replacement is distinct files", "[workload][sample_order]") {
  SampleOrder order(50, SampleOrder::Kind::Shuffled, 3);
  const std::vector<std::uint32_t> part = epoch(order, 20);
  CHECK(std::set<std::uint32_t>(part.begin(), part.end()).size() == 20);
  CHECK(std::all_of(part.begin(), part.end(), [](std::uint32_t f) { return f < 50; }));
  // One more file than the set holds is an error, not a repeat.
  epoch(order, 50);
  CHECK_THROWS(order.next());
}

TEST_CASE("the same seed gives the same orders, another seed others", "[workload][sample_order]") {
  for (const SampleOrder::Kind kind : {SampleOrder::Kind::Shuffled, SampleOrder::Kind::WithReplacement}) {
    SampleOrder a(500, kind, 1), b(500, kind, 1), c(500, kind, 2);
    for (int e = 0; e < 3; ++e) {
      const auto ea = epoch(a, 500), eb = epoch(b, 500), ec = epoch(c, 500);
      CHECK(ea == eb);
      CHECK(ea != ec);
    }
  }
}

TEST_CASE("with replacement, draws repeat files and miss others", "[workload][sample_order]") {
  // n draws from n files leave about n / e of them out: 10,000 draws, about 3,679 missed.
  SampleOrder order(10'000, SampleOrder::Kind::WithReplacement, 5);
  const std::vector<std::uint32_t> draws = epoch(order, 10'000);
  const std::size_t distinct = std::set<std::uint32_t>(draws.begin(), draws.end()).size();
  CHECK(10'000 - distinct > 3'679 - 200);
  CHECK(10'000 - distinct < 3'679 + 200);
}

TEST_CASE("in order, every epoch is 0, 1, 2, ...", "[workload][sample_order]") {
  SampleOrder order(4, SampleOrder::Kind::InOrder, 99);
  CHECK(epoch(order, 4) == std::vector<std::uint32_t>{0, 1, 2, 3});
  CHECK(epoch(order, 3) == std::vector<std::uint32_t>{0, 1, 2});
}

}  // namespace
}  // namespace pagecache::workload
