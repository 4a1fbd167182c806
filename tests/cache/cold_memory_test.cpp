// Free page reporting: memory a virtual machine's host took back is cold, and writes and first
// touches into it wait for the host (docs/model.md §6.16). FreePageReporting against a page by
// page reference of the kernel's rules, then whole hosts with times derived in comments.
#include "cache/free_page_reporting.hpp"

#include <pagecache/host.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

using namespace pagecache;
using pagecache::cache::FreePageReporting;

namespace {

constexpr std::int64_t MB = 1'000'000;

// The rules page by page: each free page knows whether it is reported, when it was freed and
// whether an application's buffer freed it; a pass reports at most ceil(free / 16) of the
// oldest unreported pages, the first a delay after a free found no pass pending, the next a
// delay later while unreported pages are left. Frees first, then the page cache's pages, then
// the buffers'. A buffer takes the unreported page a buffer freed last, else the unreported
// page freed last, else a reported one. The page cache takes the unreported page it freed
// last, else a reported one, else the unreported page a buffer freed last; without large
// folios any unreported page freed last, else a reported one.
class ReferenceReporting {
 public:
  ReferenceReporting(std::int64_t free, std::int64_t anonymous, std::int64_t warm, double delay, bool large_folios)
      : anonymous_(anonymous), delay_(delay), large_folios_(large_folios) {
    for (std::int64_t i = 0; i < free; ++i) pages_.push_back({i < free - warm, 0.0, false});
    if (warm > 0) next_ = delay;
  }
  void observe(std::int64_t free, std::int64_t anonymous, double now) {
    passes(now);
    const std::int64_t buffers = anonymous - anonymous_;
    const std::int64_t cache = (static_cast<std::int64_t>(pages_.size()) - free) - buffers;
    anonymous_ = anonymous;
    for (std::int64_t i = 0; i < -buffers; ++i) pages_.push_back({false, now, large_folios_});
    for (std::int64_t i = 0; i < -cache; ++i) pages_.push_back({false, now, false});
    if ((buffers < 0 || cache < 0) && next_ < 0) next_ = now + delay_;
    for (std::int64_t i = 0; i < cache; ++i) {
      auto best = newest_unreported([](const Page& p) { return !p.by_buffer; });
      if (best == pages_.end()) best = reported();
      if (best == pages_.end()) best = newest_unreported([](const Page&) { return true; });
      take(best);
    }
    for (std::int64_t i = 0; i < buffers; ++i) {
      auto best = newest_unreported([](const Page& p) { return p.by_buffer; });
      if (best == pages_.end()) best = newest_unreported([](const Page&) { return true; });
      if (best == pages_.end()) best = reported();
      take(best);
    }
  }
  std::int64_t cold() const { return cold_; }

 private:
  struct Page {
    bool reported;
    double freed;
    bool by_buffer;
  };
  template <typename Which>
  std::vector<Page>::iterator newest_unreported(Which which) {
    auto best = pages_.end();
    for (auto p = pages_.begin(); p != pages_.end(); ++p) {
      if (!p->reported && which(*p) && (best == pages_.end() || p->freed >= best->freed)) best = p;
    }
    return best;
  }
  std::vector<Page>::iterator reported() {
    return std::find_if(pages_.begin(), pages_.end(), [](const Page& p) { return p.reported; });
  }
  void take(std::vector<Page>::iterator page) {
    REQUIRE(page != pages_.end());
    if (page->reported) ++cold_;
    pages_.erase(page);
  }
  void passes(double now) {
    while (next_ >= 0 && next_ <= now) {
      std::int64_t budget = (static_cast<std::int64_t>(pages_.size()) + 15) / 16;
      // Oldest first: stable order of the free times, the page cache's first on a tie.
      std::vector<Page*> order;
      for (Page& p : pages_) {
        if (!p.reported) order.push_back(&p);
      }
      std::stable_sort(order.begin(), order.end(), [](const Page* a, const Page* b) {
        return a->freed < b->freed || (a->freed == b->freed && !a->by_buffer && b->by_buffer);
      });
      for (Page* p : order) {
        if (budget-- == 0) break;
        p->reported = true;
      }
      const bool left = std::any_of(pages_.begin(), pages_.end(), [](const Page& p) { return !p.reported; });
      next_ = left ? next_ + delay_ : -1.0;
    }
  }
  std::vector<Page> pages_;
  std::int64_t anonymous_;
  std::int64_t cold_ = 0;
  double delay_;
  double next_ = -1.0;
  bool large_folios_;
};

HostSpec cold_host(double cold_fault, std::int64_t freed_at_start = 0) {
  HostSpec spec{.name = "h", .cores = 4, .memory = 10'000 * MB, .memory_bandwidth = MemoryBandwidth::shared_channel(1000e6),
                .cache = CacheSettings::kernel()};
  spec.memory_bandwidth.cold_fault = cold_fault;
  spec.memory_freed_at_start = freed_at_start;
  return spec;
}

Task<void> write_at(Simulator& sim, Host& host, FileRef file, double start, double& end) {
  co_await sim.sleep(start);
  co_await host.write_file(file, 100 * MB);
  end = sim.now();
}

}  // namespace

TEST_CASE("free page reporting takes cold memory as the kernel's rules do, on random frees and allocations", "[cache][cold]") {
  std::mt19937_64 rng(20261204);
  for (const bool large_folios : {false, true}) {
    for (int trial = 0; trial < 150; ++trial) {
      const std::int64_t total = 40 + static_cast<std::int64_t>(rng() % 60);
      std::int64_t free = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(total));
      std::int64_t anonymous = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(total - free + 1));
      const std::int64_t warm = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(free + 1));
      const double delay = 1.0 + static_cast<double>(rng() % 3);
      FreePageReporting fast(free, anonymous, warm, delay, large_folios);
      ReferenceReporting reference(free, anonymous, warm, delay, large_folios);
      double now = 0.0;
      for (int step = 0; step < 60; ++step) {
        now += static_cast<double>(rng() % 5) * 0.5;
        // A new split of the memory between free, buffers and the page cache.
        free = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(total + 1));
        anonymous = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(total - free + 1));
        fast.observe(free, anonymous, now);
        reference.observe(free, anonymous, now);
        INFO("large folios " << large_folios << ", trial " << trial << ", step " << step << ", t = " << now);
        REQUIRE(fast.cold_taken() == reference.cold());
        REQUIRE(fast.warm(now) <= free);
      }
    }
  }
}

TEST_CASE("a reporting pass takes at most a sixteenth of the free memory, the first a delay after the free", "[cache][cold]") {
  // 1600 free, all just freed at 0: passes at 2, 4, 6 ... each report 100 (1600 / 16).
  FreePageReporting reporting(1600, 0, 1600, 2.0, true);
  CHECK(reporting.warm(1.99) == 1600);
  CHECK(reporting.warm(2.0) == 1500);
  CHECK(reporting.warm(5.0) == 1400);
  CHECK(reporting.warm(32.0) == 0);  // 16 passes: the whole free memory in 32 s
  // Idle, then a free at 100 s: its first pass at 102 s, not on the old grid.
  reporting.observe(2000, 0, 100.0);
  CHECK(reporting.warm(101.9) == 400);
  CHECK(reporting.warm(102.0) == 275);  // ceil(2000 / 16) = 125
  // Taking memory takes the warm memory first: 275 warm, 300 taken, 25 of them cold.
  reporting.observe(1700, 0, 102.5);
  CHECK(reporting.cold_taken() == 25);
}

TEST_CASE("a write into memory the host took back waits for it; into memory just freed it does not", "[cache][cold][host]") {
  // 100 MB written at 1000 MB/s into cold pages faulted at 500 MB/s: 1 / (1/1000 + 1/500) =
  // 333.3 MB/s, 0.3 s. Into memory the page cache freed just before (a 100 MB cached file
  // deleted at 0.5 s, written at 1.0 s): 0.1 s. Written at 5 s, after the reporting pass at
  // 2.5 s took ceil(free / 16) ~ 625 MB, more than what was warm: cold again, 0.3 s.
  for (const auto& [start, expected] : {std::pair{0.0, 0.3}, std::pair{1.0, 0.1}, std::pair{5.0, 0.3}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, cold_host(500e6));
    const DiskRef disk = host.add_disk("d", 100e6, 100e6);
    const FileRef old = host.add_file("old", 100 * MB, disk, true);
    const FileRef file = host.add_file("out", 100 * MB, disk);
    double end = 0;
    sim.spawn([](Simulator& s, Host& h, FileRef f) -> Task<void> {
      co_await s.sleep(0.5);
      co_await h.delete_file(f);
    }(sim, host, old));
    sim.spawn(write_at(sim, host, file, start, end));
    sim.run_until(start + 10.0);
    INFO("written at " << start);
    CHECK(end - start == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("memory an application's buffer freed serves the next buffer, and the page cache only without large folios", "[cache][cold][host][large_folios]") {
  // A 100 MB buffer released at 0.5 s; at 1.0 s either 100 MB written (into the page cache) or
  // a cached 100 MB file read into a new buffer. The read's buffer takes the freed pages:
  // 0.1 s. The write's cache pages: with large folios the freed single pages cannot serve
  // them, cold, 1 / (1/1000 + 1/500) = 333.3 MB/s, 0.3 s; without, 0.1 s.
  for (const auto& [large_folios, write, expected] :
       {std::tuple{true, true, 0.3}, std::tuple{false, true, 0.1}, std::tuple{true, false, 0.1}, std::tuple{false, false, 0.1}}) {
    Simulator sim;
    FairShare share(sim);
    HostSpec spec = cold_host(500e6);
    spec.cache.set("large_folios", large_folios);
    Host host(sim, share, spec);
    const DiskRef disk = host.add_disk("d", 100e6, 100e6);
    const FileRef cached = host.add_file("in", 100 * MB, disk, true);
    const FileRef out = host.add_file("out", 100 * MB, disk);
    double end = 0;
    sim.spawn([](Simulator& s, Host& h) -> Task<void> {
      co_await h.hold_memory(100 * MB);
      co_await s.sleep(0.5);
      h.release_memory(100 * MB);
    }(sim, host));
    sim.spawn([](Simulator& s, Host& h, FileRef f, bool w, double& done) -> Task<void> {
      co_await s.sleep(1.0);
      if (w) co_await h.write_file(f, 100 * MB);
      else co_await h.read_file(f, 100 * MB);
      done = s.now();
    }(sim, host, write ? out : cached, write, end));
    sim.run_until(20.0);
    INFO("large folios " << large_folios << (write ? ", write" : ", read"));
    CHECK(end - 1.0 == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("memory freed just before the start is warm; without a cold fault rate nothing is cold", "[cache][cold][host]") {
  // 100 MB freed just before the start: the write at 0 takes it, 0.1 s. Half of it: half the
  // write is cold, 1 / (1/1000 + 0.5/500) = 500 MB/s, 0.2 s. No cold_fault: 0.1 s.
  for (const auto& [cold_fault, freed, expected] : {std::tuple{500e6, 100 * MB, 0.1}, std::tuple{500e6, 50 * MB, 0.2},
                                                    std::tuple{0.0, std::int64_t{0}, 0.1}}) {
    Simulator sim;
    FairShare share(sim);
    Host host(sim, share, cold_host(cold_fault, freed));
    const FileRef file = host.add_file("out", 100 * MB, host.add_disk("d", 100e6, 100e6));
    double end = 0;
    sim.spawn(write_at(sim, host, file, 0.0, end));
    sim.run_until(10.0);
    INFO("cold_fault " << cold_fault << ", freed " << freed);
    CHECK(end == Catch::Detail::Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("a cached read into a new buffer of cold memory pays the host's faults on top of the copy", "[cache][cold][host]") {
  // 100 MB cached at the start, read into a new buffer: the copy at 1000 MB/s, the buffer's
  // pages all cold at 500 MB/s: 1 / (1/1000 + 1/500) = 333.3 MB/s, 0.3 s (first touch free).
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, cold_host(500e6));
  const FileRef file = host.add_file("in", 100 * MB, host.add_disk("d", 100e6, 100e6), true);
  double end = 0;
  sim.spawn([](Simulator& s, Host& h, FileRef f, double& done) -> Task<void> {
    co_await h.read_file(f, 100 * MB);
    done = s.now();
  }(sim, host, file, end));
  sim.run_until(10.0);
  CHECK(end == Catch::Detail::Approx(0.3).epsilon(1e-9));
}

TEST_CASE("files cached before the start take no memory freed just before it", "[cache][cold][host]") {
  // 100 MB freed just before the start and a 500 MB file cached at the start: the write at 0
  // still finds the 100 MB warm, 0.1 s (had the cached file taken them: 0.3 s).
  Simulator sim;
  FairShare share(sim);
  Host host(sim, share, cold_host(500e6, 100 * MB));
  const DiskRef disk = host.add_disk("d", 100e6, 100e6);
  host.add_file("cached", 500 * MB, disk, true);
  const FileRef file = host.add_file("out", 100 * MB, disk);
  double end = 0;
  sim.spawn(write_at(sim, host, file, 0.0, end));
  sim.run_until(10.0);
  CHECK(end == Catch::Detail::Approx(0.1).epsilon(1e-9));
}
