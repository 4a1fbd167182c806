#pragma once
// A chunk read (paper Algorithm 2; docs/model.md §4), decided in one place. Every chunk of a
// file read through the page cache (an application's local read, an NFS client's, a server's
// on a client's behalf) goes through the same steps:
//   1. What it needs (plan_read): the part not cached (the file's size less what is cached of
//      it, within the chunk) comes from the device and needs room beside the reader's buffer.
//   2. Room by eviction alone, when that is enough (evict_for_chunk). Eviction may take the
//      file's own data, so the needs are read again after it.
//   3. Otherwise the IoController writes back what eviction cannot free, evicts (evict_to_fit)
//      and, if that is still not enough, waits for transfers in flight; then step 2 again. A
//      reader in a memory group first makes room in its group (IoController::make_group_room).
//   4. The chunk starts (start_chunk): new cache data for the part from the device, a
//      re-access of the rest, the buffer taken, all before any transfer, so that concurrent
//      readers cannot count on the same free memory.
//   5. The IoController charges the transfers: device, then cache.
// Synchronous and engine-free: the waiting of step 3 and the transfers of step 5 are the
// IoController's.

#include "cache/page_cache.hpp"
#include "cache/plan.hpp"

#include <cstdint>

namespace pagecache::cache {

/// Step 2: if eviction alone makes room for the chunk as `request` describes it, evicts and
/// returns the part to read from the device; else returns -1, having evicted only when no
/// writeback was needed. `needs`, if given, receives the chunk's needs as the cache is left
/// (what step 3 must make room for).
std::int64_t evict_for_chunk(PageCache& cache, const ReadRequest& request, ReadPlan* needs = nullptr);

/// Step 3's eviction (and any room's, e.g. a task's memory): evicts what stands between
/// `required` bytes and free memory, sparing `spared`; whether they fit now.
bool evict_to_fit(PageCache& cache, std::int64_t required, FileId spared);

/// Step 4: the chunk's cache bookkeeping. `from_disk` bytes become new cache data, the rest
/// of the chunk is re-accessed from `from` (where the read's previous chunk left off,
/// PageCache::reaccess) and `request.anonymous` bytes of application memory are taken for
/// `group`, which is charged with the file if no group has it. Returns where the next chunk
/// of the same read starts. A chunk of a file held by range (`request.offset` set) reads its
/// range instead (PageCache::read_range): `from_disk` is then exactly the range's holes.
ReadCursor start_chunk(PageCache& cache, const ReadRequest& request, std::int64_t from_disk, ReadCursor from, GroupId group, double now);

}  // namespace pagecache::cache
