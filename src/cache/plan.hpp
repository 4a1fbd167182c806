#pragma once
// Plans: the paper's Algorithms 2 and 3 (docs/model.md §4) as decisions. Given the page cache as it
// is and a request, a plan says what to flush, evict, read from the device and from the cache,
// or copy into it; the IoController carries it out as transfers. Synchronous and engine-free,
// tested without a simulator.
//
// A plan holds for the state it was made from. Whatever changes that state (an eviction, the
// wait for a transfer while other processes run) calls for a new plan. Amounts <= 0 mean none,
// as the paper's flush and evict do nothing with them; plans keep them as computed. Bytes
// throughout.

#include "cache/page_cache.hpp"

#include <cstdint>

namespace pagecache::cache {

// --- The dirty thresholds ---------------------------------------------------------------------

/// The dirty thresholds, in bytes (mm/page-writeback.c, domain_dirty_limits).
struct DirtyLimits {
  std::int64_t background = 0;  ///< above it, background writeback starts
  std::int64_t thresh = 0;      ///< at it, writers not throttled flush before they write
  std::int64_t freerun = 0;     ///< (background + thresh) / 2: under it writers are never throttled
};
/// The thresholds now, as fractions of Policy::dirtyable: dirty_ratio for `thresh`,
/// dirty_background_ratio for `background`, or half of `thresh` if that ratio is not below
/// dirty_ratio (the kernel clamps it so). Truncated to whole bytes.
DirtyLimits dirty_limits(const PageCache& cache) noexcept;
/// The thresholds of a memory group's own writeback domain (mm/page-writeback.c,
/// mdtc_calculate_avail and domain_dirty_limits with a memcg domain): the same ratios of what
/// the group could hold as page cache: its cached data plus as much of its headroom under
/// memory.max / memory.high as clean memory outside the group could give it.
DirtyLimits group_dirty_limits(const PageCache& cache, GroupId group) noexcept;
/// Algorithm 3's remain_dirty: how much more data may be dirty or in writeback before the
/// dirty threshold (as balance_dirty_pages counts both); <= 0 at or over it.
std::int64_t room_under_dirty_threshold(const PageCache& cache) noexcept;

// --- Room in memory ---------------------------------------------------------------------------

/// Room for `required` bytes, as Algorithm 2 makes it: first write back what evicting cannot
/// free, then evict what is not free.
struct RoomPlan {
  std::int64_t flush = 0;  ///< required - free - evictable: dirty bytes to write back first
  std::int64_t evict = 0;  ///< required - free: clean bytes to evict
  bool fits = false;       ///< required <= free: the bytes can be taken now
};
RoomPlan plan_room(const PageCache& cache, std::int64_t required) noexcept;
/// The file that making room for a read of `file` must leave alone: none when reclaim may take
/// the file being read (the kernel's reclaim knows no file), else `file` (the paper excludes it).
FileId spared_by_read(const PageCache& cache, FileId file) noexcept;
/// Whether waiting is hopeless: no writeback and no copy into the cache in flight, so nothing
/// tied up will ever be released to make more room.
bool nothing_can_be_freed(const PageCache& cache) noexcept;

// --- Algorithm 2: a chunk read ----------------------------------------------------------------

struct ReadRequest {
  FileId file = kNoFile;
  std::int64_t file_size = 0;  ///< the caller's copy: the file's record may be out of cache
  std::int64_t bytes = 0;      ///< the chunk
  std::int64_t anonymous = 0;  ///< application memory the read takes besides the new cache data
  /// Where the chunk starts in a file held by range (PageCache::track_ranges); kWholeFile: a
  /// chunk of a whole-file read, which reads what is not cached whatever its place.
  std::int64_t offset = kWholeFile;
  static constexpr std::int64_t kWholeFile = kNoOffset;
};
struct ReadPlan {
  std::int64_t from_disk = 0;   ///< the part not cached: read from the device, then new cache data
  std::int64_t from_cache = 0;  ///< the rest, re-accessed in the cache
  std::int64_t required = 0;    ///< memory the read takes: anonymous + from_disk
  RoomPlan room;                ///< room for `required`
  FileId spared = kNoFile;      ///< what that room must not be taken from (spared_by_read)
};
/// Algorithm 2 for one chunk: the part not cached (the file's size less what is cached of it,
/// within the chunk) comes from the device and needs room beside the application's copy.
/// Evicting may take the file's own data, and then more of the chunk is not cached: plan again.
ReadPlan plan_read(const PageCache& cache, const ReadRequest& request) noexcept;
/// What a chunk's room must not be taken from: spared_by_read's for a chunk of a whole-file
/// read; nothing for a chunk of a file held by range.
FileId spared_by_chunk(const PageCache& cache, const ReadRequest& request) noexcept;
/// `plan` for `request` with its room planned again: the same parts from the device and the
/// cache (the caller knows they are), the room as memory is now.
ReadPlan replan_room(const PageCache& cache, const ReadPlan& plan, const ReadRequest& request) noexcept;

// --- Algorithm 3: a chunk write in writeback mode, not throttled ------------------------------

/// Its first step: under the dirty threshold, evict to make room for what the threshold
/// allows, then copy as much of the chunk as is free (past the threshold: a chunk may
/// overshoot it, as in the paper). At or over the threshold, nothing.
struct WriteStart {
  bool under_threshold = false;  ///< room_under_dirty_threshold > 0
  std::int64_t evict = 0;        ///< min(chunk, remain_dirty) - free; 0 over the threshold
  std::int64_t to_cache = 0;     ///< min(chunk, free) as memory is now; 0 over the threshold
};
WriteStart plan_write_start(const PageCache& cache, std::int64_t chunk) noexcept;
/// Its loop, while `remaining` bytes of the chunk are not copied: the writer, at the threshold,
/// writes back as much as it has left to write, evicts what is not free, and copies what is.
/// Less than a page when not all fits is not worth a copy (other copies in flight hold the
/// rest of memory): it waits for more instead.
struct WriteStep {
  std::int64_t flush = 0;     ///< remaining
  std::int64_t evict = 0;     ///< remaining - free
  std::int64_t to_cache = 0;  ///< min(remaining, free), 0 if that is a sliver under a page
};
WriteStep plan_write_step(const PageCache& cache, std::int64_t remaining) noexcept;

}  // namespace pagecache::cache
