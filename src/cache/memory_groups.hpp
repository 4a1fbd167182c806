#pragma once
// MemoryGroups: a host's memory groups (cgroup v2's memory controller, mm/memcontrol.c): each
// group's limits and charges, the group each file's data is charged to, and each group's files
// in reclaim order, so that a group's reclaim takes from its own files and costs what reclaim
// costs outside a group. Empty until the first group is added: a host without groups pays
// nothing. PageCache charges and moves; everyone else reads.
//
// Invariants (check): each group's cached and dirty charges are its files', the groups'
// anonymous memory is the host's, and each group's heap holds only that group's files.

#include "cache/block.hpp"
#include "cache/file_heaps.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pagecache::cache {

/// A memory group (a cgroup's memory controller): 0 is the root group, which has no limit.
using GroupId = std::uint16_t;
inline constexpr GroupId kRootGroup = 0;
/// As a reclaim or flush target: every group.
inline constexpr GroupId kAnyGroup = std::numeric_limits<GroupId>::max();

class MemoryGroups {
 public:
  /// What the host holds when its first group is added: the root group's charges from then on.
  struct HostCharges {
    std::int64_t anonymous = 0;
    std::int64_t cached = 0;
    std::int64_t dirty_and_writeback = 0;
  };
  /// A group whose memory (anonymous memory allocated for it and page cache charged to it) may
  /// not exceed `max` bytes; above `high` (memory.high; 0: none) it reclaims its own data at
  /// each charge but is never refused. Returns its id: 1, 2, ... Throws ConfigError for a
  /// limit <= 0, a high limit outside [0, max], or too many groups.
  GroupId add(std::int64_t max, std::int64_t high, const HostCharges& host);

  bool empty() const noexcept { return groups_.empty(); }
  /// 0 without groups, else the groups added and the root.
  std::size_t size() const noexcept { return groups_.size(); }
  /// The group `file`'s data is charged to (the root's unless charged to another).
  GroupId of(FileId file) const noexcept { return file < file_group_.size() ? file_group_[file] : kRootGroup; }

  // Each a group's figures; with groups only (the root's: every byte not in another group).
  /// Anonymous + cached.
  std::int64_t usage(GroupId group) const noexcept { return groups_[group].anonymous + groups_[group].cached; }
  std::int64_t cached(GroupId group) const noexcept { return groups_[group].cached; }
  /// Its data dirty or being written back (its writeback domain's NR_FILE_DIRTY + NR_WRITEBACK,
  /// as mem_cgroup_wb_stats reads them).
  std::int64_t dirty_and_writeback(GroupId group) const noexcept { return groups_[group].dirty; }
  std::int64_t max(GroupId group) const noexcept { return groups_[group].max; }
  /// What the group may still take before memory.max or memory.high, whichever is lower
  /// (mem_cgroup_wb_stats' headroom); >= 0.
  std::int64_t ceiling_headroom(GroupId group) const noexcept;
  /// How far the group is above memory.high after taking `bytes` more (<= 0: not above; the
  /// root and a group without memory.high: 0).
  std::int64_t over_high(GroupId group, std::int64_t bytes) const noexcept;
  /// What the group may still take before its limit, free memory aside (the root, and any group
  /// on a host without groups: unlimited).
  std::int64_t headroom(GroupId group) const noexcept;

  // --- Charges: PageCache's, as its blocks and application memory change ------------------
  void charge(FileId file, std::int64_t bytes) noexcept { if (!empty()) groups_[of(file)].cached += bytes; }
  void charge_dirty(FileId file, std::int64_t bytes) noexcept { if (!empty()) groups_[of(file)].dirty += bytes; }
  void charge_anonymous(GroupId group, std::int64_t bytes) noexcept { groups_[group].anonymous += bytes; }
  std::int64_t anonymous(GroupId group) const noexcept { return groups_[group].anonymous; }
  /// `file`, charged to the root until now with `cached` bytes of which `unclean` dirty or in
  /// writeback, is charged to `group` from now on.
  void move(FileId file, GroupId group, std::int64_t cached, std::int64_t unclean);
  /// Per LRU list, a heap per group of the group's files with clean data not being written,
  /// keyed as PageCache's own heap (the root's heap unused).
  FileHeaps& reclaimable(ListKind kind) noexcept { return reclaimable_[static_cast<std::size_t>(kind)]; }
  const FileHeaps& reclaimable(ListKind kind) const noexcept { return reclaimable_[static_cast<std::size_t>(kind)]; }

  /// Throws InvariantError unless each group's charges equal `cached` and `unclean` (its files'
  /// sums, by group), the groups' anonymous memory is `anonymous` (the host's), and each heap's
  /// files are its group's.
  void check(const std::vector<std::int64_t>& cached, const std::vector<std::int64_t>& unclean, std::int64_t anonymous) const;

 private:
  struct Group {
    std::int64_t max = 0;
    std::int64_t high = 0;  // 0: none
    std::int64_t anonymous = 0;
    std::int64_t cached = 0;
    std::int64_t dirty = 0;  // of `cached`: dirty or in writeback
  };
  std::vector<Group> groups_;
  std::vector<GroupId> file_group_;
  std::array<FileHeaps, 2> reclaimable_;  // by ListKind
};

}  // namespace pagecache::cache
