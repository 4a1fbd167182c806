// ReportActivity: bytes and pauses per time bucket, with the number of buckets bounded by
// merging neighbours, which must keep every sum.

#include "report/report_activity.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

using pagecache::EvictionEvent;
using pagecache::FlushCause;
using pagecache::FlushEvent;
using pagecache::ThrottleEvent;
using pagecache::report::ReportActivity;

namespace {

std::int64_t flushed(const ReportActivity& a, FlushCause cause) {
  std::int64_t sum = 0;
  for (const auto& b : a.buckets()) sum += b.flushed[static_cast<std::size_t>(cause)];
  return sum;
}

}  // namespace

TEST_CASE("events in the first buckets land in the 1 ms bucket of their time", "[report][activity]") {
  ReportActivity a;
  CHECK_FALSE(a.recorded());
  a.on_flush({0, 0.0005, FlushCause::Background, 100});
  a.on_flush({1, 0.0025, FlushCause::Expiry, 7});
  a.on_eviction({0, 0.0025, 40});
  REQUIRE(a.buckets().size() == 3);
  CHECK(a.width() == 1e-3);
  CHECK(a.buckets()[0].flushed[static_cast<std::size_t>(FlushCause::Background)] == 100);
  CHECK(a.buckets()[2].flushed[static_cast<std::size_t>(FlushCause::Expiry)] == 7);
  CHECK(a.buckets()[2].evicted == 40);
  CHECK(a.recorded());
}

TEST_CASE("an event past the last bucket merges neighbours in pairs, keeping every sum", "[report][activity]") {
  // 512 buckets of 1 ms cover [0, 0.512): an event at 1.5 s needs widths 1, 2, 4 ms (2.048 s).
  ReportActivity a;
  for (int i = 0; i < 512; ++i) a.on_flush({0, (i + 0.5) * 1e-3, FlushCause::DirtyLimit, i + 1});
  REQUIRE(a.buckets().size() == 512);
  a.on_flush({0, 1.5, FlushCause::Reclaim, 1000});
  CHECK(a.width() == Approx(4e-3));
  CHECK(a.buckets().size() <= ReportActivity::kMaxBuckets);
  CHECK(flushed(a, FlushCause::DirtyLimit) == 512 * 513 / 2);
  // The first 4 ms bucket holds the first four 1 ms buckets: 1 + 2 + 3 + 4.
  CHECK(a.buckets()[0].flushed[static_cast<std::size_t>(FlushCause::DirtyLimit)] == 10);
  CHECK(a.buckets()[375].flushed[static_cast<std::size_t>(FlushCause::Reclaim)] == 1000);  // 1.5 / 0.004
}

TEST_CASE("randomised events over 10^4 s: bounded buckets and exact sums", "[report][activity][random]") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> time(0.0, 1e4);
  std::uniform_int_distribution<std::int64_t> bytes(0, 1 << 30);
  ReportActivity a;
  std::int64_t expected_flush = 0, expected_evict = 0;
  double expected_pause = 0.0;
  double t = 0.0;
  for (int i = 0; i < 5000; ++i) {
    t = std::min(1e4, t + time(rng) / 2500.0);  // increasing, as a run reports them
    const std::int64_t b = bytes(rng);
    a.on_flush({0, t, FlushCause::Background, b});
    a.on_eviction({1, t, b / 2});
    a.on_throttle({0, t * 0.999, t});
    expected_flush += b;
    expected_evict += b / 2;
    expected_pause += t - t * 0.999;
  }
  a.on_end(t);
  CHECK(a.buckets().size() <= ReportActivity::kMaxBuckets);
  CHECK(static_cast<double>(a.buckets().size()) * a.width() > t);
  CHECK(flushed(a, FlushCause::Background) == expected_flush);
  std::int64_t evicted = 0;
  double paused = 0.0;
  for (const auto& b : a.buckets()) {
    evicted += b.evicted;
    paused += b.throttled;
  }
  CHECK(evicted == expected_evict);
  CHECK(paused == Approx(expected_pause).epsilon(1e-9));
}

TEST_CASE("a throttling pause is split over the buckets it spans", "[report][activity]") {
  // [0.5 ms, 2.5 ms]: 0.5 ms in bucket 0, 1 ms in bucket 1, 0.5 ms in bucket 2.
  ReportActivity a;
  a.on_throttle({0, 0.0005, 0.0025});
  REQUIRE(a.buckets().size() == 3);
  CHECK(a.buckets()[0].throttled == Approx(0.0005));
  CHECK(a.buckets()[1].throttled == Approx(0.001));
  CHECK(a.buckets()[2].throttled == Approx(0.0005));
}

TEST_CASE("events at bucket edges land where t / width puts them", "[report][activity]") {
  // The bucket found for the previous event is reused inside its safe interior: each time
  // within a few ulps of an edge comes right after an event in the bucket below, then right
  // after one in the bucket above, and must land in floor(t / width) either way (t = 9 ms
  // less an ulp is such a time: below 9 x 1 ms, yet its quotient rounds to 9).
  ReportActivity a;
  std::vector<std::int64_t> expected(ReportActivity::kMaxBuckets, 0);
  std::int64_t bytes = 1;
  auto flush = [&](double t) {
    a.on_flush({0, t, FlushCause::Background, bytes});
    expected[static_cast<std::size_t>(std::floor(t / 1e-3))] += bytes;
    bytes = bytes * 3 % 1000003;
  };
  for (int k = 1; k < 511; ++k) {
    double t = k * 1e-3;
    for (int step = 0; step < 3; ++step) t = std::nextafter(t, 0.0);
    for (int step = 0; step < 7; ++step, t = std::nextafter(t, 1.0)) {
      flush((k - 0.5) * 1e-3);
      flush(t);
      flush((k + 0.5) * 1e-3);
      flush(t);
    }
  }
  REQUIRE(a.width() == 1e-3);
  for (std::size_t i = 0; i < a.buckets().size(); ++i) {
    INFO("bucket " << i);
    CHECK(a.buckets()[i].flushed[static_cast<std::size_t>(FlushCause::Background)] == expected[i]);
  }
}
