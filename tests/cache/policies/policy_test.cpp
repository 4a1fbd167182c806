// The policy seam: which policy a CacheSettings names, what kernel and wrench_cache decide
// where they differ (docs/model.md §6, docs/wrench-cache.md), and a policy of a test's own reaching
// every decision PageCache delegates.
#include "cache/page_cache.hpp"
#include "cache/policy.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/error.hpp>

#include <pagecache/units.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

using namespace pagecache;
using namespace pagecache::cache;

namespace {

constexpr auto I = ListKind::Inactive;
constexpr auto A = ListKind::Active;

}  // namespace

TEST_CASE("a CacheSettings names its policy; an unknown name is refused with the known ones", "[policy]") {
  CHECK(make_policy(CacheSettings::kernel())->name() == "kernel");
  CHECK(make_policy(CacheSettings::paper())->name() == "wrench_cache");
  const std::vector<std::string> names = cache_policy_names();
  CHECK(std::find(names.begin(), names.end(), "kernel") != names.end());
  CHECK(std::find(names.begin(), names.end(), "wrench_cache") != names.end());
  CacheSettings s;
  s.policy = "belady";
  CHECK_THROWS_WITH(PageCache(1000, s), Catch::Contains("unknown page-cache policy 'belady'") && Catch::Contains("kernel"));
}

TEST_CASE("a policy's parameters: defaults by profile, a preset becomes its policy when one is set, an unknown one refused",
          "[policy]") {
  const PolicyDeclaration* kernel = find_cache_policy(CacheSettings::kernel().policy);
  REQUIRE(kernel != nullptr);
  REQUIRE(!kernel->parameters.empty());
  for (const PolicyParameter& p : kernel->parameters) {
    INFO(p.key);
    CHECK(cache_policy_with(p.key) == kernel);  // one owner per key
    CHECK(CacheSettings::kernel().value(p.key) == p.linux_default);
    CHECK(CacheSettings::paper().value(p.key) == p.paper_default);
    CHECK(!p.doc.empty());
  }
  // The paper profile's preset, one switch set: the kernel policy, the others still the preset's.
  CacheSettings paper = CacheSettings::paper();
  REQUIRE(!find_cache_policy(paper.policy)->preset_of.empty());
  paper.set("dirty_throttling", true);
  CHECK(paper.policy == kernel->name);
  CHECK(paper.get("dirty_throttling"));
  CHECK(!paper.get("background_writeback"));
  CacheSettings lru;
  lru.policy = "lru";
  CHECK_THROWS_WITH(lru.set("dirty_throttling", true), Catch::Contains("'dirty_throttling'") && Catch::Contains("'lru'"));
  CHECK_THROWS_WITH(CacheSettings::kernel().get("no_such_switch"), Catch::Contains("'no_such_switch'"));
}

TEST_CASE("the host model's switches: defaults by profile, owned by no policy, kept when the policy changes", "[policy]") {
  REQUIRE(!host_model_switches().empty());
  for (const PolicyParameter& p : host_model_switches()) {
    INFO(p.key);
    CHECK(cache_policy_with(p.key) == nullptr);
    CHECK(find_host_model_switch(p.key) == &p);
    CHECK(CacheSettings::kernel().value(p.key) == p.linux_default);
    CHECK(CacheSettings::paper().value(p.key) == p.paper_default);
    CHECK(!p.doc.empty());
    for (const PolicyDeclaration& policy : cache_policies()) {
      CacheSettings s = CacheSettings::kernel();
      s.policy = std::string(policy.name);
      const bool flipped = !std::get<bool>(p.linux_default);
      s.set(p.key, flipped);  // every policy, a preset too, takes it and stays itself
      CHECK(s.policy == policy.name);
      CHECK(s.get(p.key) == flipped);
    }
  }
  CHECK(find_host_model_switch("two_touch_activation") == nullptr);
}

TEST_CASE("kernel and wrench_cache decide activation differently", "[policy]") {
  // Data read from the device, then read again once. The kernel (two-touch activation): the
  // first read referenced it, the second activates it. Written data is not referenced: read
  // once it stays inactive, only marked. WRENCH-cache activates any re-read data. (File 2's
  // 300 inactive bytes keep active <= 2 x inactive: no balancing.)
  for (const bool kernel : {true, false}) {
    PageCache cache(10000, kernel ? CacheSettings::kernel() : CacheSettings::paper());
    cache.set_checking(true);
    cache.add_clean(2, 300, 0.0);
    cache.add_read(0, 100, 0.0);
    cache.add_clean(1, 100, 0.0);
    cache.reaccess(0, 100, 1.0);
    cache.reaccess(1, 100, 1.0);
    CHECK(cache.file(0).in(A) == 100);
    CHECK(cache.file(1).in(A) == (kernel ? 0 : 100));
    CHECK(cache.file(1).in(I) == (kernel ? 100 : 0));
  }
}

TEST_CASE("kernel and wrench_cache count dirtyable and evictable memory differently", "[policy]") {
  // 1000 bytes: 100 anonymous, 200 clean and 300 dirty inactive, 50 reserved for a copy.
  // free = 1000 - 100 - 500 - 50 = 350. Kernel: dirtyable = free + cached + reserved = 900,
  // evictable = clean inactive = 200. WRENCH-cache: dirtyable = free + cached - dirty = 550,
  // evictable = every inactive byte = 500.
  for (const bool kernel : {true, false}) {
    PageCache cache(1000, kernel ? CacheSettings::kernel() : CacheSettings::paper());
    cache.allocate_anonymous(100);
    cache.add_clean(0, 200, 0.0);
    cache.add_dirty(1, 300, 0.0);
    cache.reserve(50);
    CHECK(cache.policy().dirtyable(cache) == (kernel ? 900 : 550));
    CHECK(cache.policy().evictable(cache) == (kernel ? 200 : 500));
  }
}

TEST_CASE("kernel reclaim ages the active list; wrench_cache evicts active data in place", "[policy]") {
  // Inactive: file 0 clean 100. Active: file 1 clean 100, then file 2 clean 100 (re-read in
  // that order). Evicting 250: both take file 0's 100, then the oldest active data, file 1's
  // 100, then 50 of file 2's. The kernel deactivates what it reclaims from the active list:
  // the 50 of file 2 left over was deactivated with the part evicted, so it is inactive.
  for (const bool kernel : {true, false}) {
    CacheSettings s = kernel ? CacheSettings::kernel() : CacheSettings::paper();
    s.set("two_touch_activation", false);  // so that one re-read activates under both
    PageCache cache(10000, s);
    cache.set_checking(true);
    cache.add_clean(0, 100, 0.0);
    cache.add_clean(1, 100, 0.0);
    cache.add_clean(2, 100, 0.0);
    cache.reaccess(1, 100, 1.0);
    cache.reaccess(2, 100, 1.0);
    CHECK(cache.evict(250, kNoFile) == 250);
    CHECK(cache.file(0).cached() == 0);
    CHECK(cache.file(1).cached() == 0);
    CHECK(cache.file(2).cached() == 50);
    CHECK(cache.file(2).in(I) == (kernel ? 50 : 0));
    CHECK(cache.totals().evicted == 250);
  }
}

namespace {

// A policy of the test's own: every decision counted, answers chosen to be visible.
class CountingPolicy final : public Policy {
 public:
  mutable int rereads = 0, reclaims = 0, expiries = 0, dirtyables = 0;
  Reread on_reread = Reread::Refresh;
  // What the notifications reported, in order.
  struct Eviction {
    FileId file;
    ListKind from;
    std::int64_t bytes;
    bool operator==(const Eviction&) const = default;
  };
  std::vector<Eviction> evictions;
  std::vector<std::pair<FileId, std::int64_t>> misses;
  std::vector<FileId> drops;
  std::string_view name() const noexcept override { return "counting"; }
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override {
    ++rereads;
    return on_reread;
  }
  Balance balance() const noexcept override { return Balance::AfterReads; }
  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    ++reclaims;
    return cache.walks().evict_clean(ListKind::Inactive, amount, excluded, false);
  }
  std::int64_t evictable(const PageCache&) const noexcept override { return 7; }
  bool reclaim_may_take_file_being_read() const noexcept override { return true; }
  BlockId next_expired(PageCache& cache, double) const override {
    ++expiries;
    return cache.walks().oldest_dirty();
  }
  bool splits_flushed_block_in_place() const noexcept override { return true; }
  bool background_writeback() const noexcept override { return true; }
  bool throttles_writers() const noexcept override { return true; }
  std::int64_t dirtyable(const PageCache&) const noexcept override {
    ++dirtyables;
    return 1234;
  }
  void evicted(const PageCache&, const Evicted& data) override { evictions.push_back({data.file, data.from, data.bytes}); }
  void missed(const PageCache&, FileId file, std::int64_t bytes) override { misses.emplace_back(file, bytes); }
  void dropped(const PageCache&, FileId file) override { drops.push_back(file); }
};

}  // namespace

TEST_CASE("PageCache asks its policy at each decision", "[policy]") {
  auto owned = std::make_unique<CountingPolicy>();
  const CountingPolicy& policy = *owned;
  PageCache cache(1000, CacheSettings::kernel(), {}, std::move(owned));
  cache.set_checking(true);
  CHECK(cache.policy().name() == "counting");
  // Refresh: file 0 re-read moves to the MRU end of the inactive list, behind file 1, and
  // nothing is active; eviction then takes file 1 first.
  cache.add_clean(0, 100, 0.0);
  cache.add_clean(1, 100, 0.0);
  cache.reaccess(0, 100, 1.0);
  CHECK(policy.rereads == 1);
  CHECK(cache.list(A).bytes() == 0);
  CHECK(cache.list(I).blocks().begin()->file == 1);
  CHECK(cache.evict(100, kNoFile) == 100);
  CHECK(policy.reclaims == 1);
  CHECK(cache.file(1).cached() == 0);
  CHECK(cache.file(0).cached() == 100);
  CHECK(cache.policy().evictable(cache) == 7);
  CHECK(cache.policy().dirtyable(cache) == 1234);
  CHECK(policy.dirtyables == 1);
  cache.add_dirty(2, 50, 1.0);
  const PageCache::Flushed taken = cache.flush_expired_block(5.0);
  CHECK(policy.expiries == 1);
  CHECK(taken.file == 2);
  CHECK(taken.bytes == 50);
}

TEST_CASE("PageCache tells its policy of each block evicted, each read from a device and each file dropped", "[policy]") {
  auto owned = std::make_unique<CountingPolicy>();
  CountingPolicy& policy = *owned;
  PageCache cache(1000, CacheSettings::kernel(), {}, std::move(owned));
  cache.set_checking(true);
  using E = CountingPolicy::Eviction;
  // Misses are device reads only: file 0's 100 and file 2's 50; an empty read, file 1's data
  // cached from the start and file 3's written data are none.
  cache.add_read(0, 100, 0.0);
  cache.add_read(0, 0, 0.0);
  cache.add_clean(1, 100, 0.0);
  cache.add_read(2, 50, 0.0);
  cache.add_dirty(3, 10, 0.0);
  CHECK(policy.misses == std::vector<std::pair<FileId, std::int64_t>>{{0, 100}, {2, 50}});
  // Reclaim of 150 from the inactive list, LRU first: file 0's block, then 50 of file 1's.
  CHECK(cache.evict(150, kNoFile) == 150);
  CHECK(policy.evictions == std::vector<E>{{0, I, 100}, {1, I, 50}});
  // File 2 re-read is activated; active aging of 30 evicts its first 30 bytes, from the
  // active list (the other 20 go to the inactive list, not evicted: not reported).
  policy.on_reread = Policy::Reread::Activate;
  cache.reaccess(2, 50, 1.0);
  CHECK(cache.walks().deactivate_oldest(30, kNoFile, false) == 30);
  CHECK(policy.evictions.back() == E{2, A, 30});
  CHECK(policy.evictions.size() == 3);
  CHECK(cache.file(2).in(I) == 20);
  // Dropping file 1 frees its 50 bytes: a drop, not an eviction.
  cache.drop_file(1);
  CHECK(policy.drops == std::vector<FileId>{1});
  CHECK(policy.evictions.size() == 3);
  CHECK(cache.file(1).cached() == 0);
}

TEST_CASE("every parameter a policy declares is documented: docs/linux-profile.md and docs/model.md name it", "[policy][docs]") {
  const auto read = [](const char* doc) {
    std::ifstream in(std::filesystem::path(PCSIM_SOURCE_DIR) / "docs" / doc);
    REQUIRE(in);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string profile = read("linux-profile.md");
  const std::string model = read("model.md");
  for (const PolicyParameter& p : host_model_switches()) {
    INFO(p.key);
    CHECK(model.find(std::string("`") + std::string(p.key) + "`") != std::string::npos);
  }
  for (const PolicyDeclaration& policy : cache_policies()) {
    CHECK(model.find(std::string("`") + std::string(policy.name) + "`") != std::string::npos);
    for (const PolicyParameter& p : policy.parameters) {
      INFO(policy.name << "." << p.key);
      const std::string key = std::string("`") + std::string(p.key) + "`";
      // In backquotes, or in a section's heading.
      bool in_heading = false;
      std::istringstream lines(profile);
      for (std::string line; std::getline(lines, line);) in_heading = in_heading || (line.rfind("## ", 0) == 0 && line.find(p.key) != std::string::npos);
      CHECK((profile.find(key) != std::string::npos || in_heading));
      CHECK(model.find(key) != std::string::npos);
    }
  }
}

TEST_CASE("a policy's parameters are typed: a value of another kind or out of bounds is refused, and each kind is written as read",
          "[policy]") {
  CacheSettings s = CacheSettings::kernel();
  s.policy = "mglru";
  CHECK(s.integer("refault_batch") == 64);
  s.set("refault_batch", std::int64_t{32});
  CHECK(s.integer("refault_batch") == 32);
  CHECK_THROWS_WITH(s.set("refault_batch", true), Catch::Contains("'refault_batch' is an integer from 1 to 4096, got true"));
  CHECK_THROWS_WITH(s.set("refault_batch", std::int64_t{0}), Catch::Contains("from 1 to 4096, got 0"));
  CHECK_THROWS_WITH(s.set("refault_batch", 0.5), Catch::Contains("an integer"));
  CHECK_THROWS_WITH(s.get("refault_batch"), Catch::Contains("not a switch"));
  CHECK_THROWS_WITH(CacheSettings::kernel().integer("two_touch_activation"), Catch::Contains("not an integer"));
  CHECK_THROWS_WITH(CacheSettings::kernel().set("two_touch_activation", std::int64_t{1}), Catch::Contains("is a switch"));
  CHECK(s.integer("refault_batch") == 32);  // a refused value leaves the parameter as it was

  // Sizes and ratios, as a declaration would give them.
  constexpr PolicyParameter size{"window", std::int64_t{128 << 10}, std::int64_t{128 << 10}, "a size", ParameterKind::Size, 4096, 1 << 30};
  constexpr PolicyParameter ratio{"share", 0.5, 0.5, "a ratio", ParameterKind::Ratio, 0.0, 1.0};
  CHECK(size.accepts(std::int64_t{4096}));
  CHECK(!size.accepts(std::int64_t{4095}));
  CHECK(!size.accepts(0.5));
  CHECK(ratio.accepts(1.0));
  CHECK(!ratio.accepts(1.5));
  CHECK(!ratio.accepts(std::int64_t{1}));
  CHECK(format_parameter(ParameterKind::Size, std::int64_t{128 << 10}) == "\"128 KiB\"");
  CHECK(units::parse_size("128 KiB") == 128 << 10);
  CHECK(format_parameter(ParameterKind::Ratio, 0.25) == "0.25");
  CHECK(format_parameter(ParameterKind::Integer, std::int64_t{64}) == "64");
  CHECK(format_parameter(ParameterKind::Switch, false) == "false");
}
