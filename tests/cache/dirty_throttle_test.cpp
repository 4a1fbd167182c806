// DirtyThrottle without a run: what a writer does next for a given page cache, as the kernel's
// balance_dirty_pages decides it (docs/model.md §6.4).
#include "cache/dirty_throttle.hpp"
#include "cache/file_table.hpp"

#include <pagecache/cache_settings.hpp>

#include <catch2/catch.hpp>

namespace pagecache::cache {
namespace {

constexpr std::int64_t MB = 1'000'000;
constexpr double kDiskBw = 500e6;

// A 1 GB host with the kernel's settings: thresh 200 MB, background 100 MB, freerun 150 MB, and
// with the limit at the threshold (at rest) the setpoint at 175 MB.
struct Host {
  Simulator sim;
  PageCache cache{1000 * MB, CacheSettings::kernel()};
  FileTable files;
  Flusher flusher{sim, cache, files};
  DirtyThrottle throttle{sim, cache, flusher};
  Host() {
    cache.add_file(0);
    throttle.at_rest();
  }
};

}  // namespace

TEST_CASE("the kernel's thresholds of the test host", "[throttle]") {
  Host h;
  const DirtyLimits l = dirty_limits(h.cache);
  CHECK(l.thresh == 200 * MB);
  CHECK(l.background == 100 * MB);
  CHECK(l.freerun == 150 * MB);
}

TEST_CASE("under the setpoint a writer copies at once, its pages reserved", "[throttle]") {
  Host h;
  h.cache.add_dirty(0, 120 * MB, 0.0);
  DirtyThrottle::Writer writer(h.throttle, kDiskBw);
  const DirtyThrottle::Step step = writer.next(50 * MB);  // 120 + 50 <= 175
  CHECK(step.kind == DirtyThrottle::Step::Copy);
  CHECK(step.to_cache == 50 * MB);
  CHECK(h.cache.memory().reserved == 50 * MB);
}

TEST_CASE("at the setpoint a writer is paced at the device's bandwidth, shared by the throttled writers", "[throttle]") {
  Host h;
  h.cache.add_dirty(0, 175 * MB, 0.0);
  DirtyThrottle::Writer first(h.throttle, kDiskBw);
  const DirtyThrottle::Step alone = first.next(100 * MB);
  REQUIRE(alone.kind == DirtyThrottle::Step::Pause);
  CHECK(alone.rate == Approx(kDiskBw));  // position ratio 1 at the setpoint
  CHECK(alone.pause == Approx(100 * MB / kDiskBw));
  {
    DirtyThrottle::Writer second(h.throttle, kDiskBw);
    const DirtyThrottle::Step shared = second.next(100 * MB);
    REQUIRE(shared.kind == DirtyThrottle::Step::Pause);
    CHECK(shared.rate == Approx(kDiskBw / 2));
  }
  // The second writer's chunk is over: the first is paced alone again.
  CHECK(first.next(100 * MB).rate == Approx(kDiskBw));
}

TEST_CASE("above the setpoint the pace falls with the cube of the distance, to nothing at the limit", "[throttle]") {
  Host h;
  h.cache.add_dirty(0, 180 * MB, 0.0);
  DirtyThrottle::Writer writer(h.throttle, kDiskBw);
  const DirtyThrottle::Step step = writer.next(10 * MB);
  REQUIRE(step.kind == DirtyThrottle::Step::Pause);
  // x = (175 - 180) / (200 - 175) = -0.2: 1 + x^3 = 0.992.
  CHECK(step.rate == Approx(kDiskBw * 0.992));
  Host full;
  full.cache.add_dirty(0, 200 * MB, 0.0);
  DirtyThrottle::Writer held(full.throttle, kDiskBw);
  const DirtyThrottle::Step none = held.next(10 * MB);
  REQUIRE(none.kind == DirtyThrottle::Step::Pause);
  CHECK(none.rate == 0.0);
  CHECK(none.pause == 1.0);  // it looks again every second
}

TEST_CASE("a paused writer copies the bytes its pauses earned", "[throttle]") {
  Host h;
  h.cache.add_dirty(0, 175 * MB, 0.0);
  DirtyThrottle::Writer writer(h.throttle, kDiskBw);
  const DirtyThrottle::Step pause = writer.next(20 * MB);
  REQUIRE(pause.kind == DirtyThrottle::Step::Pause);
  writer.paused(pause);
  const DirtyThrottle::Step copy = writer.next(20 * MB);
  CHECK(copy.kind == DirtyThrottle::Step::Copy);
  CHECK(copy.to_cache == 20 * MB);
}

TEST_CASE("a writer with no free memory makes room first", "[throttle]") {
  Host h;
  h.cache.allocate_anonymous(900 * MB);
  h.cache.add_dirty(0, 100 * MB, 0.0);  // no free memory, nothing clean to evict
  DirtyThrottle::Writer writer(h.throttle, kDiskBw);
  // 100 MB dirty of 100 MB dirtyable is over every threshold: a pause first; earned, room.
  DirtyThrottle::Step step = writer.next(10 * MB);
  if (step.kind == DirtyThrottle::Step::Pause) {
    writer.paused({step.kind, 0, 1e9, 1.0});  // as if it had earned the chunk
    step = writer.next(10 * MB);
  }
  CHECK(step.kind == DirtyThrottle::Step::MakeRoom);
}

}  // namespace pagecache::cache
