#include "cache/plan.hpp"

#include <algorithm>

namespace pagecache::cache {

namespace {

DirtyLimits limits_of(const CacheSettings& s, std::int64_t available) noexcept {
  const double base = static_cast<double>(std::max<std::int64_t>(available, 0));
  DirtyLimits l;
  l.thresh = static_cast<std::int64_t>(s.dirty_ratio * base);
  l.background = s.dirty_background_ratio < s.dirty_ratio ? static_cast<std::int64_t>(s.dirty_background_ratio * base) : l.thresh / 2;
  l.freerun = (l.background + l.thresh) / 2;
  return l;
}

}  // namespace

DirtyLimits dirty_limits(const PageCache& cache) noexcept { return limits_of(cache.settings(), cache.policy().dirtyable(cache)); }

DirtyLimits group_dirty_limits(const PageCache& cache, GroupId group) noexcept {
  const std::int64_t filepages = cache.groups().cached(group);
  const std::int64_t clean = filepages - std::min(filepages, cache.groups().dirty_and_writeback(group));
  const std::int64_t global_dirtyable = std::max<std::int64_t>(cache.policy().dirtyable(cache), 0);
  const std::int64_t global_clean = global_dirtyable - std::min(global_dirtyable, dirty_and_writeback(cache));
  const std::int64_t other_clean = global_clean - std::min(global_clean, clean);
  return limits_of(cache.settings(), filepages + std::min(cache.groups().ceiling_headroom(group), other_clean));
}

std::int64_t room_under_dirty_threshold(const PageCache& cache) noexcept {
  return dirty_limits(cache).thresh - dirty_and_writeback(cache);
}

RoomPlan plan_room(const PageCache& cache, std::int64_t required) noexcept {
  const std::int64_t free = cache.free();
  return RoomPlan{.flush = required - free - cache.policy().evictable(cache), .evict = required - free, .fits = required <= free};
}

FileId spared_by_read(const PageCache& cache, FileId file) noexcept {
  return cache.policy().reclaim_may_take_file_being_read() ? kNoFile : file;
}

FileId spared_by_chunk(const PageCache& cache, const ReadRequest& request) noexcept {
  // A read by parts may evict the file's own other parts under every model: sparing a file
  // larger than memory would leave a random reader of it no room at all.
  return request.offset == ReadRequest::kWholeFile ? spared_by_read(cache, request.file) : kNoFile;
}

bool nothing_can_be_freed(const PageCache& cache) noexcept { return cache.memory().writeback == 0 && cache.memory().reserved == 0; }

ReadPlan plan_read(const PageCache& cache, const ReadRequest& request) noexcept {
  const std::int64_t from_disk = request.offset == ReadRequest::kWholeFile
                                     ? std::clamp<std::int64_t>(request.file_size - cache.file(request.file).cached(), 0, request.bytes)
                                     : request.bytes - cache.ranges().cached_in(request.file, request.offset, request.bytes);
  const std::int64_t required = request.anonymous + from_disk;
  return ReadPlan{.from_disk = from_disk,
                  .from_cache = request.bytes - from_disk,
                  .required = required,
                  .room = plan_room(cache, required),
                  .spared = spared_by_chunk(cache, request)};
}

ReadPlan replan_room(const PageCache& cache, const ReadPlan& plan, const ReadRequest& request) noexcept {
  ReadPlan again = plan;
  again.room = plan_room(cache, plan.required);
  again.spared = spared_by_chunk(cache, request);
  return again;
}

WriteStart plan_write_start(const PageCache& cache, std::int64_t chunk) noexcept {
  const std::int64_t remain_dirty = room_under_dirty_threshold(cache);
  if (remain_dirty <= 0) return WriteStart{};
  return WriteStart{.under_threshold = true, .evict = std::min(chunk, remain_dirty) - cache.free(), .to_cache = std::min(chunk, cache.free())};
}

WriteStep plan_write_step(const PageCache& cache, std::int64_t remaining) noexcept {
  std::int64_t to_cache = std::min(remaining, cache.free());
  if (to_cache < remaining && to_cache < kPageSize) to_cache = 0;
  return WriteStep{.flush = remaining, .evict = remaining - cache.free(), .to_cache = to_cache};
}

}  // namespace pagecache::cache
