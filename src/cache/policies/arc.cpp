// The arc policy: a simple ARC (Megiddo & Modha, "ARC: A Self-Tuning, Low Overhead Replacement
// Cache", FAST 2003) at pcsim's granularity, bytes of files. T1 (data seen once) is the inactive
// list, T2 (seen twice or more) the active one: any re-read activates. The policy keeps ARC's
// ghost lists of its own, B1 and B2 (bytes of each file evicted from T1, T2), and ARC's target p
// for T1: a miss on a file with ghost bytes in B1 raises p, in B2 lowers it; reclaim takes from
// T1 while T1 is above p, else from T2. Writeback and dirty limits are the kernel's
// (KernelWriteback), as lru's.
//
// Where it departs from ARC: data read back after a ghost hit enters T1 (PageCache's reads add
// to the inactive list), not T2; PageCache still balances T2 <= 2 x T1 after every read; the
// ghost lists together hold at most the cache's size, and T1 + B1 is not capped as in ARC.

#include "cache/policies/kernel_writeback.hpp"

#include <pagecache/cache_policies.hpp>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <iterator>
#include <limits>
#include <list>
#include <memory>
#include <unordered_map>

namespace pagecache::cache {


namespace {

// A ghost list: bytes of files evicted, oldest first, each run stamped with when it was evicted.
// Without offsets a file's ghost bytes are interchangeable: a hit forgets the file's oldest.
class GhostList {
 public:
  std::int64_t bytes() const noexcept { return bytes_; }
  std::int64_t bytes(FileId file) const noexcept {
    const auto f = files_.find(file);
    return f == files_.end() ? 0 : f->second.bytes;
  }
  /// When the oldest bytes were evicted, or the largest stamp if there are none.
  std::uint64_t oldest() const noexcept { return order_.empty() ? std::numeric_limits<std::uint64_t>::max() : order_.front().stamp; }

  /// `bytes` of `file` evicted at `stamp` (stamps increase across both ghost lists).
  void push(FileId file, std::int64_t bytes, std::uint64_t stamp) {
    PerFile& f = files_[file];
    f.bytes += bytes;
    bytes_ += bytes;
    // Evicted right after the newest run, of the same file: the same run (its stamp the later).
    if (!order_.empty() && order_.back().file == file && order_.back().stamp + 1 == stamp) {
      order_.back().bytes += bytes;
      order_.back().stamp = stamp;
      return;
    }
    order_.push_back({file, bytes, stamp});
    f.runs.push_back(std::prev(order_.end()));
  }

  /// Forgets `bytes` (at most what it holds) of `file`'s ghosts, its oldest first.
  void forget(FileId file, std::int64_t bytes) {
    while (bytes > 0) {
      const auto f = files_.find(file);  // again: taking its last run erases it
      if (f == files_.end()) return;
      bytes -= take(f, f->second.runs.front(), bytes);
    }
  }

  /// Forgets up to `most` bytes of the oldest run; returns how many.
  std::int64_t forget_oldest(std::int64_t most) {
    if (order_.empty()) return 0;
    return take(files_.find(order_.front().file), order_.begin(), most);
  }

 private:
  struct Run {
    FileId file;
    std::int64_t bytes;
    std::uint64_t stamp;  // when its newest bytes were evicted
  };
  using Order = std::list<Run>;
  struct PerFile {
    std::deque<Order::iterator> runs;  // its runs, oldest first
    std::int64_t bytes = 0;
  };
  using Files = std::unordered_map<FileId, PerFile>;

  // Takes up to `most` bytes off `run`, the oldest run of the file `f`; returns how many.
  std::int64_t take(Files::iterator f, Order::iterator run, std::int64_t most) {
    const std::int64_t taken = std::min(most, run->bytes);
    run->bytes -= taken;
    f->second.bytes -= taken;
    bytes_ -= taken;
    if (run->bytes == 0) {
      order_.erase(run);
      f->second.runs.pop_front();
      if (f->second.runs.empty()) files_.erase(f);
    }
    return taken;
  }

  Order order_;
  Files files_;
  std::int64_t bytes_ = 0;
};

class ArcPolicy final : public KernelWriteback {
 public:

  std::string_view name() const noexcept override { return "arc"; }

  // A hit in T1 or T2 moves the data to T2's most recently used end; no referenced marks.
  bool read_is_first_touch() const noexcept override { return false; }
  Reread reread(const Block&) const noexcept override { return Reread::Activate; }
  Balance balance() const noexcept override { return Balance::AfterReads; }

  bool spares_files_being_written() const noexcept override { return false; }
  std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) override {
    // ARC's REPLACE: T1's least recently used data while T1 is above p, then T2's, evicted in
    // place (deactivating it would move T2's dirty data into T1 and inflate it against p);
    // then T1's again when T2 has too little clean data.
    const std::int64_t above_target = std::max<std::int64_t>(cache.list(ListKind::Inactive).bytes() - p_, 0);
    std::int64_t evicted = cache.walks().evict_clean(ListKind::Inactive, std::min(amount, above_target), excluded, false);
    evicted += cache.walks().evict_clean(ListKind::Active, amount - evicted, excluded, false);
    evicted += cache.walks().evict_clean(ListKind::Inactive, amount - evicted, excluded, false);
    return evicted;
  }
  std::int64_t evictable(const PageCache& cache) const noexcept override {
    return cache.list(ListKind::Inactive).bytes(BlockState::Clean) + cache.list(ListKind::Active).bytes(BlockState::Clean);
  }

  void evicted(const PageCache& cache, const Evicted& data) override {
    (data.from == ListKind::Inactive ? b1_ : b2_).push(data.file, data.bytes, ++stamp_);
    trim(capacity(cache));
  }
  void missed(const PageCache& cache, FileId file, std::int64_t bytes) override {
    // Without offsets, the bytes read are taken as the file's B1 ghosts first, then its B2
    // ones. Each ghost byte hit moves p by ARC's delta, from the ghost lists as they were.
    const std::int64_t c = capacity(cache);
    const std::int64_t in_b1 = std::min(bytes, b1_.bytes(file));
    const std::int64_t in_b2 = std::min(bytes - in_b1, b2_.bytes(file));
    const std::int64_t raise = scaled(in_b1, b2_.bytes(), b1_.bytes(), c);
    const std::int64_t lower = scaled(in_b2, b1_.bytes(), b2_.bytes(), c);
    p_ = std::clamp(p_ + raise - lower, std::int64_t{0}, c);
    b1_.forget(file, in_b1);
    b2_.forget(file, in_b2);
    trim(c);
  }
  void dropped(const PageCache&, FileId file) override {
    b1_.forget(file, b1_.bytes(file));
    b2_.forget(file, b2_.bytes(file));
  }

 private:
  // ARC's c: what the page cache may hold now, all memory but the applications'.
  static std::int64_t capacity(const PageCache& cache) noexcept {
    const MemoryState memory = cache.memory();
    return memory.free + memory.cached + memory.reserved;
  }

  // ARC's delta for `hit` ghost bytes of a list of `own` bytes, the other holding `other`:
  // hit x max(1, other / own), at most `cap` (in double: hit x other may overflow).
  static std::int64_t scaled(std::int64_t hit, std::int64_t other, std::int64_t own, std::int64_t cap) noexcept {
    if (hit == 0 || other <= own) return std::min(hit, cap);
    return static_cast<std::int64_t>(std::min(static_cast<double>(hit) * static_cast<double>(other) / static_cast<double>(own),
                                              static_cast<double>(cap)));
  }

  // Forgets the oldest ghosts, of either list, until both together hold at most `c` bytes.
  void trim(std::int64_t c) {
    while (b1_.bytes() + b2_.bytes() > c) {
      GhostList& older = b1_.oldest() < b2_.oldest() ? b1_ : b2_;
      older.forget_oldest(b1_.bytes() + b2_.bytes() - c);
    }
  }

  GhostList b1_;                 // evicted from T1
  GhostList b2_;                 // evicted from T2
  std::int64_t p_ = 0;           // the target size of T1, in [0, c]
  std::uint64_t stamp_ = 0;      // evictions so far: orders the ghosts of both lists
};

}  // namespace

extern const PolicyRegistration kArcPolicy{
    .declaration = {
        .name = "arc",
        .doc = "ARC (Megiddo & Modha 2003) over the two lists: ghost lists of evicted data steer reclaim between once- and twice-seen data",
        .parameters = {},
        .preset_of = {},
    },
    .make = [](const CacheSettings&) -> std::unique_ptr<Policy> { return std::make_unique<ArcPolicy>(); },
};

}  // namespace pagecache::cache
