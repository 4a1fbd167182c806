// RequestStream: the requests of each pattern, and the permutation behind random orders.
#include "workload/request_pattern.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

using namespace pagecache;
using namespace pagecache::workload;

namespace {

// Every request of `epochs` epochs.
std::vector<ByteRange> all(const RequestPattern& pattern, std::int64_t epochs = 1) {
  RequestStream stream(pattern);
  std::vector<ByteRange> out;
  for (std::int64_t e = 0; e < epochs; ++e) {
    stream.start_epoch(e);
    for (ByteRange r; stream.next(r);) out.push_back(r);
    CHECK(static_cast<std::int64_t>(out.size()) == (e + 1) * stream.per_epoch());
  }
  return out;
}

std::vector<std::int64_t> offsets(const std::vector<ByteRange>& requests, std::size_t from, std::size_t to) {
  std::vector<std::int64_t> out;
  for (std::size_t i = from; i < to; ++i) out.push_back(requests[i].offset);
  return out;
}

}  // namespace

TEST_CASE("the permutation behind random orders is one, for any count and key", "[workload][pattern]") {
  for (std::uint64_t n : {1u, 2u, 3u, 5u, 16u, 17u, 100u, 1000u, 4097u, 65536u}) {
    const int half = permutation_half_bits(n);
    CHECK((std::uint64_t{1} << (2 * half)) >= n);
    for (std::uint64_t key : {0ull, 1ull, 0xDEADBEEFull}) {
      std::vector<bool> seen(n, false);
      for (std::uint64_t i = 0; i < n; ++i) {
        const std::uint64_t p = permute(i, n, key, half);
        REQUIRE(p < n);
        REQUIRE_FALSE(seen[p]);
        seen[p] = true;
      }
    }
  }
}

TEST_CASE("sequential requests cut the region in order, the last one shorter, once per epoch", "[workload][pattern]") {
  const auto requests = all({.kind = RequestPattern::Kind::Sequential, .offset = 100, .length = 1000, .request = 300}, 2);
  REQUIRE(requests.size() == 8);
  CHECK(requests[0] == ByteRange{100, 300});
  CHECK(requests[3] == ByteRange{1000, 100});
  CHECK(requests[4] == ByteRange{100, 300});
}

TEST_CASE("random requests without replacement: every slot once per epoch, each epoch its own order", "[workload][pattern]") {
  const RequestPattern pattern{.kind = RequestPattern::Kind::Random, .offset = 0, .length = 1000 * 4096, .request = 4096, .seed = 7};
  const auto requests = all(pattern, 3);
  REQUIRE(requests.size() == 3000);
  for (std::size_t epoch = 0; epoch < 3; ++epoch) {
    auto got = offsets(requests, epoch * 1000, (epoch + 1) * 1000);
    std::sort(got.begin(), got.end());
    for (std::int64_t i = 0; i < 1000; ++i) REQUIRE(got[static_cast<std::size_t>(i)] == i * 4096);
  }
  CHECK(offsets(requests, 0, 1000) != offsets(requests, 1000, 2000));
  // Not the identity, nor nearly: most requests are far from their slot.
  std::int64_t in_place = 0;
  for (std::int64_t i = 0; i < 1000; ++i) in_place += requests[static_cast<std::size_t>(i)].offset == i * 4096;
  CHECK(in_place < 20);
  // The same seed, the same requests; another seed, others.
  CHECK(offsets(all(pattern, 3), 0, 3000) == offsets(requests, 0, 3000));
  RequestPattern other = pattern;
  other.seed = 8;
  CHECK(offsets(all(other), 0, 1000) != offsets(requests, 0, 1000));
}

TEST_CASE("random requests with replacement draw `count` slots, some twice", "[workload][pattern]") {
  const auto requests =
      all({.kind = RequestPattern::Kind::Random, .offset = 4096, .length = 100 * 4096, .request = 4096, .count = 500, .replacement = true, .seed = 1});
  REQUIRE(requests.size() == 500);
  std::set<std::int64_t> distinct;
  for (const ByteRange& r : requests) {
    REQUIRE(r.offset >= 4096);
    REQUIRE(r.offset + r.length <= 101 * 4096);
    REQUIRE(r.offset % 4096 == 0);
    distinct.insert(r.offset);
  }
  CHECK(distinct.size() < 500);
  CHECK(distinct.size() > 90);  // 500 draws of 100 slots miss one with chance 100 (0.99)^500 < 1 %
}

TEST_CASE("strided requests: one every stride from the offset, as many as fit", "[workload][pattern]") {
  const auto requests = all({.kind = RequestPattern::Kind::Strided, .offset = 10, .length = 1000, .request = 100, .stride = 250});
  REQUIRE(requests.size() == 4);  // at 10, 260, 510, 760 (1010 would end past 1010)
  CHECK(requests[3] == ByteRange{760, 100});
}

TEST_CASE("ranges are read in order, each cut into requests", "[workload][pattern]") {
  const auto requests = all({.kind = RequestPattern::Kind::Ranges, .request = 100, .ranges = {{500, 250}, {0, 100}}});
  REQUIRE(requests.size() == 4);
  CHECK(requests[0] == ByteRange{500, 100});
  CHECK(requests[2] == ByteRange{700, 50});
  CHECK(requests[3] == ByteRange{0, 100});
}
