#pragma once
// Flusher: the writeback process. Periodic writeback (paper Algorithm 1): every
// writeback_interval it writes, one block at a time, the dirty data older than dirty_expire,
// inactive list first, sharing the disks with everything else; then it sleeps for what is
// left of the interval. Background writeback (the kernel's, mm/page-writeback.c; switched by
// CacheSettings::background_writeback): whenever dirty data exceeds dirty_background_ratio of
// dirtyable memory, it writes the oldest dirty data until it is back under that threshold;
// and whenever a memory group's dirty data exceeds the group's own background threshold
// (group_dirty_limits), the group's oldest dirty data (wb_over_bg_thresh with a memcg domain).
//
// When no dirty data is left it parks instead of ticking, and is woken by notify_dirty(); it
// then resumes on the same cadence (its ticks stay at the same times as if it had ticked all
// along), so a simulation without dirty data ends instead of ticking forever.

#include "cache/file_table.hpp"
#include "cache/page_cache.hpp"

#include <pagecache/event.hpp>
#include <pagecache/simulator.hpp>

#include <deque>
#include <optional>
#include <vector>

namespace pagecache::cache {

class Flusher {
 public:
  Flusher(Simulator& sim, PageCache& cache, const FileTable& files) noexcept
      : sim_(&sim), cache_(&cache), files_(&files) {}
  Flusher(const Flusher&) = delete;
  Flusher& operator=(const Flusher&) = delete;

  /// Starts the periodic process; its first tick is at now().
  void start();
  /// New dirty data (of memory group `group`): wakes the flusher if it is parked or if
  /// background writeback is due, the group's included.
  void notify_dirty(GroupId group = kRootGroup);
  /// Bytes written back by the flusher so far.
  std::int64_t flushed_bytes() const noexcept { return flushed_; }

 private:
  Task<void> periodic();
  bool background_due() const;
  /// Memory group `group` is over its own background threshold.
  bool group_background_due(GroupId group) const;
  /// Writes back what the group has above its background threshold; returns how much.
  Task<std::int64_t> write_group(GroupId group);
  /// Writes back the least recently used dirty block older than `cutoff` (if any).
  Task<void> write_block(double cutoff);

  Simulator* sim_;
  PageCache* cache_;
  const FileTable* files_;
  std::optional<Event> wake_;
  std::deque<GroupId> due_groups_;  // groups over their own background threshold, to write back
  std::vector<bool> queued_;        // by GroupId: in due_groups_
  std::int64_t flushed_ = 0;
  bool started_ = false;
  bool parked_ = false;
};

}  // namespace pagecache::cache
