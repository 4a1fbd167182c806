#pragma once
// CacheSettings: how one host's page cache behaves (docs/model.md §3, §6).
//
// The kernel knobs keep the kernel's names and are stored in SI units (ratios as fractions,
// times in seconds). `policy` names the model of the decisions in which the kernel and
// WRENCH-cache, the paper's implementation, differ (docs/wrench-cache.md); the
// switches are the parameters of the `kernel` policy, each turning one of the kernel's
// behaviours into WRENCH-cache's. CacheSettings::paper() reproduces WRENCH-cache (the `paper`
// profile, policy `wrench_cache`); CacheSettings::kernel() follows the kernel (the `linux`
// profile; not named linux(), which GNU dialects of C++ predefine as a macro).

#include <string>
#include <vector>

namespace pagecache {

enum class WriteMode { Writeback, Writethrough };

struct CacheSettings {
  WriteMode write_mode = WriteMode::Writeback;
  /// vm.dirty_ratio: a writer may dirty at most this fraction of dirtyable memory.
  double dirty_ratio = 0.2;
  /// vm.dirty_background_ratio: above this fraction background writeback starts.
  double dirty_background_ratio = 0.1;
  /// vm.dirty_expire_centisecs, in seconds: dirty data older than this is written back.
  double dirty_expire = 30.0;
  /// vm.dirty_writeback_centisecs, in seconds: period of the flusher.
  double writeback_interval = 5.0;

  /// The decisions' model: "kernel", "wrench_cache" or "lru" (src/cache/policies/).
  std::string policy = "kernel";

  // --- Parameters of the kernel policy (the others ignore them) ----------------------------
  /// Background writeback (mm/page-writeback.c, wb_over_bg_thresh): above
  /// dirty_background_ratio of dirtyable memory the flusher writes the oldest dirty data at
  /// once, concurrently with the writers, until dirty data is back under that threshold. Off,
  /// as the paper: dirty data waits for dirty_expire or for a writer to hit dirty_ratio.
  bool background_writeback = true;
  /// Dirty throttling (mm/page-writeback.c, balance_dirty_pages): a writer never flushes
  /// itself. It writes at memory speed while dirty + writeback data is under the kernel's
  /// setpoint, halfway between the freerun ceiling ((dirty_ratio + dirty_background_ratio) / 2)
  /// and dirty_ratio; there it is paused until writeback frees quota, so writers together
  /// dirty data as fast as the devices clean it. Needs background_writeback (the flusher does
  /// the writing); without it, writers flush as in the paper. Off, as the paper: a writer at
  /// dirty_ratio flushes a chunk's worth itself, then writes the chunk.
  bool dirty_throttling = true;
  /// The periodic flusher writes expired data oldest first, as kupdate-style writeback takes
  /// expired inodes in the order they were dirtied (fs/fs-writeback.c, b_dirty ordered by
  /// dirtied_when), in O(1) per block. Off, as the paper's Algorithm 1: expired blocks of the
  /// inactive list, then of the active list, in LRU order.
  bool expire_oldest_first = true;
  /// Two-touch activation (mm/swap.c, mark_page_accessed): data read from a device is marked
  /// referenced by that read; cached data read again is activated only if referenced, else it
  /// is just marked. Written data is not referenced: written then read once, it stays
  /// inactive. Off, as the paper: any re-read activates.
  bool two_touch_activation = true;
  /// Files being written keep their pages: eviction takes other clean data first, and the
  /// clean data of files open for writing only when nothing else is left (the paper observed
  /// this of the kernel: a file's freshly written pages outlive older data). Off, as the paper.
  bool protect_files_being_written = true;
  /// Dirty thresholds are fractions of free + cached memory, as the kernel's dirtyable memory
  /// (mm/page-writeback.c, global_dirtyable_memory). Off: free + cached - dirty, the paper's.
  bool dirtyable_memory = true;
  /// Eviction makes room from clean inactive data, and a read's "evictable" memory is that
  /// clean inactive data (mm/vmscan.c scans the inactive list); when none is left, the oldest
  /// active data is deactivated and reclaimed if clean (shrink_active_list). Off, as
  /// WRENCH-cache: eviction goes on to clean active data in place, and "evictable" counts
  /// every inactive byte.
  bool reclaim_inactive_only = true;
  /// Making room for a read may evict (and flush) the file being read, oldest data first, as
  /// the kernel's reclaim knows no file. Off, as the paper's Algorithm 2: the file being read
  /// is excluded, so a file whose copy and buffer exceed memory cannot be read.
  bool reclaim_may_take_file_being_read = true;
  /// A partly flushed block is split in place. Off, as WRENCH-cache: its flushed part moves
  /// to the most-recently-used end of the inactive list.
  bool flush_splits_in_place = true;
  /// The lists are balanced (active <= 2 x inactive) after every change. Off, as
  /// WRENCH-cache: after reads only.
  bool balance_after_every_change = true;
  /// Copies into and out of the page cache hold a core of their host while they run,
  /// competing with computations for the cores (Memory::copy_on). Off, as the paper: copies
  /// take memory bandwidth only. Off in the linux profile too (see docs/linux-profile.md).
  bool copies_hold_cores = false;
  /// The page cache allocates multi-page folios (mm/filemap.c, __filemap_get_folio with the
  /// write's or readahead's order; ext4 and xfs on Linux 6.x), so single pages an
  /// application's buffer freed serve other buffers, and the page cache only when no other
  /// free memory is left. It matters only where freed memory goes cold (free page reporting,
  /// docs/model.md §6.16). Off: any free memory serves any allocation.
  bool large_folios = true;

  /// The paper's model as WRENCH-cache implements it: dirty ratio 0.4, 5 s interval, 30 s
  /// expiry, and WRENCH-cache's reading of the paper where the paper is ambiguous.
  static CacheSettings paper() {
    CacheSettings s;
    s.policy = "wrench_cache";
    s.dirty_ratio = 0.4;
    s.dirty_background_ratio = 0.1;
    s.dirty_expire = 30.0;
    s.writeback_interval = 5.0;
    s.dirtyable_memory = false;
    s.background_writeback = false;
    s.dirty_throttling = false;
    s.expire_oldest_first = false;
    s.two_touch_activation = false;
    s.protect_files_being_written = false;
    s.reclaim_inactive_only = false;
    s.reclaim_may_take_file_being_read = false;
    s.flush_splits_in_place = false;
    s.balance_after_every_change = false;
    s.large_folios = false;
    return s;
  }
  /// The kernel's behaviour with its default knobs.
  static CacheSettings kernel() { return CacheSettings{}; }
};

/// The names CacheSettings::policy may take, in the order they were registered.
std::vector<std::string> cache_policy_names();

}  // namespace pagecache
