// PageCache: memory groups (cgroup v2 memory.max, first cut): a group's limit and charges.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace pagecache::cache {

GroupId PageCache::add_group(std::int64_t max, std::int64_t high) {
  if (max <= 0) throw ConfigError(fmt::format("a memory group's limit must be > 0, got {} bytes", max));
  if (high < 0 || high > max) throw ConfigError(fmt::format("a memory group's high limit must be between 0 and its limit ({} bytes), got {}", max, high));
  if (groups_.empty()) {
    // The root group holds everything so far.
    groups_.push_back(Group{.max = std::numeric_limits<std::int64_t>::max(), .anonymous = anonymous_, .cached = cached(), .dirty = dirty_and_writeback()});
  }
  if (groups_.size() == kAnyGroup) throw ConfigError("too many memory groups");
  groups_.push_back(Group{.max = max, .high = high});
  for (FileHeaps& files : group_reclaimable_) files.resize(groups_.size());
  return static_cast<GroupId>(groups_.size() - 1);
}

void PageCache::charge_file(FileId file, GroupId group) {
  if (groups_.empty() || group == kRootGroup || group_of(file) != kRootGroup) return;
  PC_ASSERT(group < groups_.size());
  if (file >= file_group_.size()) file_group_.resize(static_cast<std::size_t>(file) + 1, kRootGroup);
  const std::int64_t bytes = cached(file);
  groups_[kRootGroup].cached -= bytes;
  groups_[group].cached += bytes;
  const std::int64_t unclean = dirty(file) + writeback(file);  // walks the file: once per file
  groups_[kRootGroup].dirty -= unclean;
  groups_[group].dirty += unclean;
  file_group_[file] = group;
  // Its clean data, reclaimable in the group from now on.
  if (!index_clean_ || file >= files_.size() || files_[file].writers > 0) return;
  const FileEntry& entry = files_[file];
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    const FileCleanOrder& clean = kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
    if (!clean.empty()) reclaimable(kind, true).lower(group, file, blocks_[clean.front()].order);
  }
}

std::int64_t PageCache::group_usage(GroupId group) const noexcept {
  if (groups_.empty()) return anonymous_ + cached();
  return groups_[group].anonymous + groups_[group].cached;
}

std::int64_t PageCache::group_room(GroupId group) const noexcept {
  if (groups_.empty() || group == kRootGroup) return free();
  return std::min(groups_[group].max - group_usage(group), free());
}

std::int64_t PageCache::group_ceiling_headroom(GroupId group) const noexcept {
  const Group& g = groups_[group];
  const std::int64_t ceiling = g.high > 0 ? std::min(g.max, g.high) : g.max;
  return std::max<std::int64_t>(ceiling - group_usage(group), 0);
}

std::int64_t PageCache::group_over_high(GroupId group, std::int64_t bytes) const noexcept {
  if (groups_.empty() || group == kRootGroup || groups_[group].high == 0) return 0;
  return group_usage(group) + bytes - groups_[group].high;
}

std::int64_t PageCache::group_headroom(GroupId group) const noexcept {
  return groups_.empty() || group == kRootGroup ? std::numeric_limits<std::int64_t>::max() : groups_[group].max - group_usage(group);
}

}  // namespace pagecache::cache
