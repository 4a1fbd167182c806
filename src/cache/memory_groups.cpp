// MemoryGroups: the groups' limits and charges, and the invariants that tie them to the files.

#include "cache/memory_groups.hpp"

#include "engine/check.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

GroupId MemoryGroups::add(std::int64_t max, std::int64_t high, const HostCharges& host) {
  if (max <= 0) throw ConfigError(fmt::format("a memory group's limit must be > 0, got {} bytes", max));
  if (high < 0 || high > max) throw ConfigError(fmt::format("a memory group's high limit must be between 0 and its limit ({} bytes), got {}", max, high));
  if (groups_.empty()) {
    // The root group holds everything so far.
    groups_.push_back(Group{.max = std::numeric_limits<std::int64_t>::max(), .anonymous = host.anonymous, .cached = host.cached, .dirty = host.dirty_and_writeback});
  }
  if (groups_.size() == kAnyGroup) throw ConfigError("too many memory groups");
  groups_.push_back(Group{.max = max, .high = high});
  for (FileHeaps& files : reclaimable_) files.resize(groups_.size());
  return static_cast<GroupId>(groups_.size() - 1);
}

void MemoryGroups::move(FileId file, GroupId group, std::int64_t cached, std::int64_t unclean) {
  PC_ASSERT(!groups_.empty() && group != kRootGroup && group < groups_.size() && of(file) == kRootGroup);
  if (file >= file_group_.size()) file_group_.resize(static_cast<std::size_t>(file) + 1, kRootGroup);
  groups_[kRootGroup].cached -= cached;
  groups_[group].cached += cached;
  groups_[kRootGroup].dirty -= unclean;
  groups_[group].dirty += unclean;
  file_group_[file] = group;
}

std::int64_t MemoryGroups::ceiling_headroom(GroupId group) const noexcept {
  const Group& g = groups_[group];
  const std::int64_t ceiling = g.high > 0 ? std::min(g.max, g.high) : g.max;
  return std::max<std::int64_t>(ceiling - usage(group), 0);
}

std::int64_t MemoryGroups::over_high(GroupId group, std::int64_t bytes) const noexcept {
  if (groups_.empty() || group == kRootGroup || groups_[group].high == 0) return 0;
  return usage(group) + bytes - groups_[group].high;
}

std::int64_t MemoryGroups::headroom(GroupId group) const noexcept {
  return groups_.empty() || group == kRootGroup ? std::numeric_limits<std::int64_t>::max() : groups_[group].max - usage(group);
}

void MemoryGroups::check(const std::vector<std::int64_t>& cached, const std::vector<std::int64_t>& unclean, std::int64_t anonymous) const {
  PC_ASSERT(cached.size() == groups_.size() && unclean.size() == groups_.size());
  std::int64_t groups_anonymous = 0;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    PC_ASSERT_MSG(groups_[g].cached == cached[g], fmt::format("group {}: {} bytes charged, its files hold {}", g, groups_[g].cached, cached[g]));
    PC_ASSERT_MSG(groups_[g].dirty == unclean[g], fmt::format("group {}: {} bytes dirty or in writeback, its files hold {}", g, groups_[g].dirty, unclean[g]));
    PC_ASSERT_MSG(groups_[g].anonymous >= 0, fmt::format("group {}: {} bytes of anonymous memory", g, groups_[g].anonymous));
    groups_anonymous += groups_[g].anonymous;
  }
  PC_ASSERT_MSG(groups_anonymous == anonymous, "the groups' anonymous memory is not the host's");
  for (const FileHeaps& files : reclaimable_) {
    files.check();
    PC_ASSERT_MSG(files.heaps() == 1 || files.empty(kRootGroup), "the root group's heap holds files");
    for (std::size_t g = 0; g < files.heaps(); ++g) {
      files.for_each(g, [&](const FileHeaps::Entry& e) {
        PC_ASSERT_MSG(of(e.file) == g, fmt::format("file {} in group {}'s reclaimable files, charged to group {}", e.file, g, of(e.file)));
      });
    }
  }
}

}  // namespace pagecache::cache
