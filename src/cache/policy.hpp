#pragma once
// Policy: the decisions in which page-cache models differ (docs/model.md §6), kept apart from the
// page cache's state. PageCache keeps blocks, lists, files and counters and offers the walks
// over them; a Policy says which walks to take: what a re-read does, which clean data reclaim
// takes next, which expired data is written back first, what the dirty limits are fractions
// of, and whether writers are paced or flush themselves.
//
// A policy's answers to the questions without arguments never change: PageCache asks them
// once, when it is made. A policy may keep state of its own (ghost lists, a target size):
// PageCache tells it what happened to the data through the notifications at the end (evicted,
// missed, dropped; by default they do nothing), and reclaim may change it.
//
// Implementations live in src/cache/policies/, one file each defining the policy's registration
// (its declaration, pagecache/cache_policies.hpp, and factory), named in registry.cpp's list: `kernel` (the
// kernel's behaviour; its switches are the `linux` profile's ablations), the `wrench_cache`
// preset (the kernel policy with every switch at WRENCH-cache's reading of the paper, the
// `paper` profile; docs/wrench-cache.md), `lru` (one LRU list, no activation: a plain
// baseline), `clock` (second chance), `arc` (ARC over the two lists, with ghost lists of its
// own: a policy with state) and `mglru` (the kernel's generations: the lists are its two
// oldest, reads only mark, data arriving is placed by it).

#include "cache/block.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/cache_settings.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::cache {

class PageCache;

class Policy {
 public:
  virtual ~Policy() = default;
  /// The name a CacheSettings::policy gives it.
  virtual std::string_view name() const noexcept = 0;

  // --- Activation (mm/swap.c) -------------------------------------------------------------
  /// Whether the read that brings data in from a device counts as its first touch (marks it
  /// referenced, so that the next read of it may activate it).
  virtual bool read_is_first_touch() const noexcept = 0;
  /// What a read of cached data does to one of its blocks on the inactive list.
  enum class Reread : std::uint8_t {
    Activate,  ///< to the most recently used end of the active list
    Mark,      ///< marked referenced, left in place
    Refresh,   ///< to the most recently used end of the inactive list
  };
  virtual Reread reread(const Block& inactive_block) const noexcept = 0;
  /// Whether a read of cached data leaves it where it is on either list, only changing its
  /// block's policy bits to reread_bits (asked once; reread is then never asked).
  virtual bool rereads_in_place() const noexcept { return false; }
  /// The policy bits of a block read again in place.
  virtual std::uint8_t reread_bits(const Block& block) const noexcept { return block.policy_bits; }
  /// When the lists are balanced (active <= 2 x inactive).
  enum class Balance : std::uint8_t {
    AfterEveryChange,  ///< after every change of the cache
    AfterReads,        ///< after each read of a chunk
    Never,             ///< never by PageCache: the lists mean what the policy says
  };
  virtual Balance balance() const noexcept = 0;
  /// Whether arriving decides where data read from a device goes (asked once); else it goes
  /// to the inactive list, referenced if read_is_first_touch.
  virtual bool places_arrivals() const noexcept { return false; }
  /// Where the first bytes (the answer's, > 0, at most `bytes`) of `file`'s data arriving from
  /// a device go: at `offset` for a file held by range, else kNoOffset; `demand` for data a
  /// read asked for, not for data read ahead. Called before they are added.
  struct Arrival {
    std::int64_t bytes = 0;
    Placement at;
  };
  virtual Arrival arriving(const PageCache& /*cache*/, FileId /*file*/, std::int64_t /*offset*/, std::int64_t bytes, bool demand) {
    return {bytes, Placement{.list = ListKind::Inactive, .referenced = demand && read_is_first_touch(), .bits = 0}};
  }

  // --- Reclaim (mm/vmscan.c) --------------------------------------------------------------
  /// Whether reclaim spares the files being written; PageCache then keeps each file's clean
  /// blocks indexed (asked once, when the cache is made).
  virtual bool spares_files_being_written() const noexcept = 0;
  /// Evicts up to `amount` bytes of clean data, never of `excluded`, with PageCache's
  /// reclaim walks (CacheWalks: evict_clean, deactivate_oldest); returns how many bytes it evicted.
  /// Not const: a policy with state of its own may change it as it decides.
  virtual std::int64_t reclaim(PageCache& cache, std::int64_t amount, FileId excluded) = 0;
  /// Memory a read may count on freeing by eviction before it must flush.
  virtual std::int64_t evictable(const PageCache& cache) const noexcept = 0;
  /// Whether making room for a read may evict and flush the file being read.
  virtual bool reclaim_may_take_file_being_read() const noexcept = 0;

  // --- Writeback (mm/page-writeback.c, fs/fs-writeback.c) ---------------------------------
  /// The expired dirty block (entry time <= `cutoff`) the periodic flusher writes next, or
  /// kNoBlock; PageCache has checked that some dirty data has expired.
  virtual BlockId next_expired(PageCache& cache, double cutoff) const = 0;
  /// Whether the written part of a dirty block flushed in part stays in place (else it moves
  /// to the most recently used end of the inactive list).
  virtual bool splits_flushed_block_in_place() const noexcept = 0;
  /// Whether the flusher writes back at once above the background threshold.
  virtual bool background_writeback() const noexcept = 0;
  /// Whether writers at the dirty limit are paced while the flusher writes (dirty
  /// throttling) rather than flushing data themselves.
  virtual bool throttles_writers() const noexcept = 0;

  // --- Dirty limits -----------------------------------------------------------------------
  /// Memory the dirty ratios are fractions of.
  virtual std::int64_t dirtyable(const PageCache& cache) const noexcept = 0;

  // --- Notifications, for a policy with state of its own (nothing by default) -------------
  // Once per block or per read chunk, never per page: the stateless policies pay a call each.
  /// Data evicted by a reclaim walk: its file, the list it left (evict_clean's list;
  /// deactivate_oldest's victims come from the active list), its bytes, its offset (a file
  /// held by range, told to a policy that places arrivals: one load fewer per eviction for the
  /// others; else kNoOffset) and its block's policy bits.
  struct Evicted {
    FileId file = 0;
    ListKind from = ListKind::Inactive;
    std::int64_t bytes = 0;
    std::int64_t offset = 0;
    std::uint8_t bits = 0;
  };
  /// Called once per block evicted, after it is gone from `cache`.
  virtual void evicted(const PageCache& /*cache*/, const Evicted& /*data*/) {}
  /// `bytes` of `file` not in the cache were read from a device (a miss: PageCache::add_read),
  /// once per read chunk, after they are cached. Not called for data written or cached from
  /// the start (add_clean, add_dirty).
  virtual void missed(const PageCache& /*cache*/, FileId /*file*/, std::int64_t /*bytes*/) {}
  /// `file` was deleted (PageCache::drop_file): its data left the cache without eviction, and
  /// a policy forgets what it remembers of it. Called after its blocks are gone.
  virtual void dropped(const PageCache& /*cache*/, FileId /*file*/) {}
  /// Whether written_back is asked when a block's writeback ends (asked once).
  virtual bool rotates_written_back() const noexcept { return false; }
  /// A block's writeback just ended (it is clean): its new policy bits, if it goes to the
  /// front of the inactive list (the next data reclaim meets), else nothing.
  virtual std::optional<std::uint8_t> written_back(const Block& /*block*/) const noexcept { return std::nullopt; }
};

/// A policy as its file defines it for the registry (policies/registry.cpp): its declaration
/// and its factory (none for a preset: its policy's).
struct PolicyRegistration {
  PolicyDeclaration declaration;
  std::unique_ptr<Policy> (*make)(const CacheSettings& settings) = nullptr;
};

/// The policy `settings.policy` names (a preset: the policy it presets), with its parameters
/// from `settings`. Throws ConfigError for a name not registered.
std::unique_ptr<Policy> make_policy(const CacheSettings& settings);

}  // namespace pagecache::cache
