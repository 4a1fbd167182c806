// PageCache: memory groups (cgroup v2 memory.max): a file charged to a group, and the figures
// read from the cache as a whole and its groups together.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <algorithm>

namespace pagecache::cache {

GroupId PageCache::add_group(std::int64_t max, std::int64_t high) {
  return groups_.add(max, high, {.anonymous = anonymous_, .cached = cached(), .dirty_and_writeback = dirty() + writeback()});
}

void PageCache::charge_file(FileId file, GroupId group) {
  if (groups_.empty() || group == kRootGroup || groups_.of(file) != kRootGroup) return;
  PC_ASSERT(group < groups_.size());
  groups_.move(file, group, cached(file), dirty(file) + writeback(file));  // writeback walks the file: once per file
  // Its clean data, reclaimable in the group from now on.
  if (!index_clean_ || file >= files_.size() || files_[file].writers > 0) return;
  const FileEntry& entry = files_[file];
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    const FileCleanOrder& clean = kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
    if (!clean.empty()) reclaimable(kind, true).lower(group, file, blocks_[clean.front()].order);
  }
}

std::int64_t group_usage(const PageCache& cache, GroupId group) noexcept {
  if (cache.groups().empty()) {
    const MemoryState memory = cache.memory();
    return memory.anonymous + memory.cached;
  }
  return cache.groups().usage(group);
}

std::int64_t group_room(const PageCache& cache, GroupId group) noexcept {
  return std::min(cache.groups().headroom(group), cache.free());
}

}  // namespace pagecache::cache
