#include "cache/chunk_read.hpp"

#include "engine/check.hpp"

namespace pagecache::cache {

std::int64_t evict_for_chunk(PageCache& cache, const ReadRequest& request, ReadPlan* needs) {
  ReadPlan plan = plan_read(cache, request);
  const bool writeback_first = plan.room.flush > 0;
  if (!writeback_first) {
    const std::int64_t file_cached = request.offset == ReadRequest::kWholeFile ? 0 : cache.file(request.file).cached();
    cache.evict(plan.room.evict, plan.spared);
    // The eviction may have taken the file's own data. A range's holes are looked up in the
    // file's offset index, a few cache misses: only again if it did.
    if (request.offset == ReadRequest::kWholeFile || cache.file(request.file).cached() != file_cached) plan = plan_read(cache, request);
    else plan = replan_room(cache, plan, request);
  }
  if (needs != nullptr) *needs = plan;
  return !writeback_first && plan.room.fits ? plan.from_disk : -1;
}

bool evict_to_fit(PageCache& cache, std::int64_t required, FileId spared) {
  cache.evict(plan_room(cache, required).evict, spared);
  return plan_room(cache, required).fits;
}

ReadCursor start_chunk(PageCache& cache, const ReadRequest& request, std::int64_t from_disk, ReadCursor from, GroupId group, double now) {
  cache.charge_file(request.file, group);
  if (request.offset != ReadRequest::kWholeFile) {
    const std::int64_t missing = cache.read_range(request.file, request.offset, request.bytes, now);
    PC_ASSERT(missing == from_disk);
    if (request.anonymous > 0) cache.allocate_anonymous(request.anonymous, group);
    return from;
  }
  cache.add_read(request.file, from_disk, now);
  const ReadCursor next = cache.reaccess(request.file, request.bytes - from_disk, now, from);
  if (request.anonymous > 0) cache.allocate_anonymous(request.anonymous, group);
  return next;
}

}  // namespace pagecache::cache
