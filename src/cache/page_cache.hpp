#pragma once
// PageCache: the state of one host's memory as the paper's Memory Manager keeps it (docs/model.md
// §1-§3): anonymous memory, and the cached data blocks on the inactive and active LRU lists.
//
// Synchronous and engine-free: every operation takes the current time and returns at once,
// so it can be tested without a simulator. Timing (disk and memory transfers) is the
// IoController's and the Flusher's business: they ask PageCache what to move, then charge the
// transfer to the devices. PageCache is the mechanism; where models differ (what a re-read
// activates, what reclaim takes, which expired data goes first, the dirtyable memory) it asks
// its Policy (cache/policy.hpp), which acts on the lists through CacheWalks. State of its own
// lives in collaborators, each with its own invariant check: MemoryGroups (limits, charges, a
// group's reclaim order), NumaNodes (the nodes' memory, placement), FileRanges (the files held
// by byte range, their blocks by offset).
//
// Invariants (checked by check_invariants(), after every operation when set_checking(true),
// amortised in debug builds): total = free + anonymous + cached, free >= 0, 0 <= dirty <= cached,
// cached = inactive + active, every list's byte counter equals its block sum, every block is
// in exactly one LRU list and in its file's list for that LRU list; with the clean index, every
// clean block is in its file's clean list for that LRU list, and every file not being written
// that has clean data there is in reclaimable_ (when the policy spares files being written);
// with NUMA nodes, each node's counters equal its blocks' sums and its free memory is >= 0.

#include "cache/block.hpp"
#include "cache/block_list.hpp"
#include "cache/block_pool.hpp"
#include "cache/cache_walks.hpp"
#include "cache/file_heaps.hpp"
#include "cache/file_ranges.hpp"
#include "cache/lru_list.hpp"
#include "cache/memory_groups.hpp"
#include "cache/numa_nodes.hpp"
#include "cache/policy.hpp"
#include "cache/tracer.hpp"

#include <pagecache/cache_settings.hpp>
#include <pagecache/memory_state.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

namespace pagecache::cache {

inline constexpr FileId kNoFile = std::numeric_limits<FileId>::max();
/// As an offset: none, the data of a whole-file read or write.
inline constexpr std::int64_t kNoOffset = -1;

/// Where a read of a file in chunks left off in the page cache (PageCache::reaccess).
struct ReadCursor {
  BlockId block = kNoBlock;  ///< the file's first inactive block not yet touched, or the last one touched
  bool after = false;        ///< start after `block` (it was the last inactive block, touched)
  std::uint64_t order = 0;   ///< its order key then: a block moved or reused since has another
};

/// How a host's memory is laid out for its page cache.
struct MemoryLayout {
  int nodes = 1;                       ///< NUMA nodes sharing it evenly, 1 to kMaxNodes (docs/model.md §6.20)
  std::int64_t page_size = kPageSize;  ///< reclaim takes files held by range in pages of this (> 0)
};

/// Who is told what happens in the cache: each may be left empty.
struct CacheListeners {
  /// Memory that was tied up may be reclaimable now (a writeback ended, a copy in flight
  /// landed, application memory was released): writers and readers that found nothing to
  /// reclaim wait for it.
  std::function<void()> progress;
  /// After every change of the memory state (memory profiles, peaks).
  std::function<void()> change;
  /// With the free and the anonymous memory, after every change (free page reporting).
  std::function<void(std::int64_t free, std::int64_t anonymous)> free_memory;
  /// Where this host's flushes, evictions and throttling pauses are reported (evict() reports
  /// its own; the flusher and the I/O controller report theirs through it).
  Tracer tracer;
};

/// One file's data in the cache.
struct FileUse {
  std::int64_t inactive = 0;
  std::int64_t active = 0;
  std::int64_t dirty = 0;  ///< of inactive + active
  std::int64_t cached() const noexcept { return inactive + active; }
  std::int64_t in(ListKind kind) const noexcept { return kind == ListKind::Inactive ? inactive : active; }
};

/// What the cache has done so far.
struct CacheTotals {
  std::int64_t evicted = 0;     ///< bytes evicted
  std::int64_t peak_dirty = 0;  ///< the most dirty data at once (data becomes dirty only when written)
};

class PageCache {
 public:
  /// A cache of `total_memory` bytes laid out as `layout` says, under `policy` (e.g. a test's
  /// own), or when none is given the policy `settings.policy` names (make_policy).
  PageCache(std::int64_t total_memory, const CacheSettings& settings, MemoryLayout layout = {}, std::unique_ptr<Policy> policy = nullptr);
  PageCache(const PageCache&) = delete;
  PageCache& operator=(const PageCache&) = delete;
  ~PageCache();

  const CacheSettings& settings() const noexcept { return settings_; }
  const Policy& policy() const noexcept { return *policy_; }
  CacheListeners& listeners() noexcept { return listeners_; }
  /// Runs check_invariants() after every mutating operation (tests). Debug builds check by
  /// default, amortised: one operation in blocks/4, as a full check visits every block.
  void set_checking(bool on) noexcept { checking_ = on, amortised_ = false; }

  // --- Memory -----------------------------------------------------------------------------
  MemoryState memory() const noexcept;
  std::int64_t free() const noexcept { return total_ - anonymous_ - cached() - reserved_; }
  const LruList& list(ListKind kind) const noexcept { return kind == ListKind::Inactive ? inactive_ : active_; }
  /// Takes `bytes` of free memory for application buffers. Throws SimulationError if there
  /// is not that much free memory (the caller makes room first).
  void allocate_anonymous(std::int64_t bytes, GroupId group = kRootGroup);
  void release_anonymous(std::int64_t bytes, GroupId group = kRootGroup);

  // --- Memory groups (cgroup v2 memory.max; mm/memcontrol.c) ------------------------------
  const MemoryGroups& groups() const noexcept { return groups_; }
  /// MemoryGroups::add, the root group taking what the host holds when the first is added.
  GroupId add_group(std::int64_t max, std::int64_t high = 0);
  /// Charges the data of `file` to `group` unless a group has it already. The kernel charges
  /// each page to the group of the task that brought it in (first touch); pcsim charges a
  /// whole file to the first group that caches any of it.
  void charge_file(FileId file, GroupId group);

  // --- NUMA nodes (docs/model.md §6.20; page_cache_nodes.cpp) ------------------------------
  const NumaNodes& nodes() const noexcept { return nodes_; }
  /// The node of the thread whose operations follow (NumaNodes::toucher).
  void touch_from(NodeId node) noexcept { nodes_.touch_from(node); }

  // --- Per file ---------------------------------------------------------------------------
  FileUse file(FileId file) const noexcept;
  /// Bytes of `file` being written back now.
  std::int64_t writeback(FileId file) const noexcept;
  /// Makes the entry of a file its host has just registered. Optional (any id gets its entry
  /// when first cached), but entries made during the run move every file's list heads when
  /// their array grows: with 10^5 applications each move relinks blocks long out of cache.
  void add_file(FileId file) { file_entry(file); }

  // --- Cache contents ---------------------------------------------------------------------
  /// New clean data (written through, or in the cache from the start): a clean block at the
  /// MRU end of the inactive list.
  void add_clean(FileId file, std::int64_t bytes, double now);
  /// New data read from a device by an application: like add_clean, and this read is its
  /// first touch if the policy says so (Policy::read_is_first_touch); the policy is told of
  /// the miss (Policy::missed).
  void add_read(FileId file, std::int64_t bytes, double now);
  /// New data written: a dirty block (entry time `now`) at the MRU end of the inactive list.
  void add_dirty(FileId file, std::int64_t bytes, double now);
  /// Takes `bytes` of free memory for a copy into the cache that is about to start (throws
  /// SimulationError if not free); commit_dirty turns them into dirty data when it ends.
  void reserve(std::int64_t bytes);
  /// The copy of `bytes` reserved ended: they become dirty data of `file`, entered `now`, written
  /// at `offset` of a file held by range (as write_range writes), else after its data.
  void commit_dirty(FileId file, std::int64_t bytes, double now, std::int64_t offset = kNoOffset);
  /// Re-access of `bytes` cached bytes of `file` by a read: inactive blocks first, then
  /// active ones, least recently used first. Clean data read is merged into one block at the
  /// MRU end of the active list; dirty blocks move there individually, keeping their entry
  /// times. A block read only in part is split and only the part read moves. What happens
  /// to each inactive block is the policy's call (Policy::reread): activated, only marked
  /// referenced, or moved to the MRU end of the inactive list.
  ///
  /// A read of a file in chunks touches each page once: a chunk's re-access starts where the
  /// previous chunk's ended, past the blocks it only marked (`from`, as the previous call
  /// returned; the default starts at the least recently used block). Returns where the next
  /// chunk of the same read starts.
  ReadCursor reaccess(FileId file, std::int64_t bytes, double now, ReadCursor from = {});

  // --- Byte ranges (docs/model.md §6.19) ---------------------------------------------------
  // From a file's first access by parts, its blocks carry offsets (FileRanges); whole-file I/O pays nothing.
  /// From now on the file's data is held by range; what it has takes ranges from offset 0,
  /// least recently used first, inactive list then active. Idempotent.
  void track_ranges(FileId file);
  /// The files held by range and their blocks' offsets (FileRanges::tracked, cached_in).
  const FileRanges& ranges() const noexcept { return ranges_; }
  /// A read of the range: each cached part re-accessed as reaccess() does (only the part read
  /// moves), then each hole new data read as add_read() makes it. Returns the holes' bytes.
  std::int64_t read_range(FileId file, std::int64_t offset, std::int64_t bytes, double now);
  /// Readahead: the holes become clean data at the inactive list's MRU end, untouched (as the
  /// kernel adds readahead pages). Returns the bytes added.
  std::int64_t read_ahead(FileId file, std::int64_t offset, std::int64_t bytes, double now);
  /// POSIX_FADV_DONTNEED: the range's clean data is dropped (dirty data and data in writeback
  /// stay). Returns the bytes dropped.
  std::int64_t drop_clean_range(FileId file, std::int64_t offset, std::int64_t bytes);
  /// A write of the range, its copy done: holes become new dirty data, clean data and data in
  /// writeback dirty again (entered `now`; the write in flight ends for the rest of its data),
  /// dirty data stays dirty with its entry time; all to the inactive list's MRU end, by offset.
  /// Returns the holes' bytes.
  std::int64_t write_range(FileId file, std::int64_t offset, std::int64_t bytes, double now);

  /// Bytes of one file taken for writing to its device.
  struct Flushed {
    FileId file;
    std::int64_t bytes;
    std::uint64_t token = 0;  // identifies the write in progress
  };
  /// Takes up to `amount` dirty bytes for writing back, least recently used first, inactive
  /// list then active list, skipping `excluded`: they are in writeback (neither dirty nor
  /// evictable) until end_writeback. Appends a part per run of one file's data to `out`, each
  /// a write of its own (the caller writes each, then ends it), and returns the total.
  /// `group`: only that group's data (a group's own reclaim at its limit; not the root's).
  std::int64_t flush(std::int64_t amount, FileId excluded, std::vector<Flushed>& out, GroupId group = kAnyGroup);
  /// Takes for writing back a dirty block whose entry time is <= `cutoff` (the one
  /// Policy::next_expired chooses), or returns {kNoFile, 0}. The periodic flusher writes
  /// expired data one block at a time.
  Flushed flush_expired_block(double cutoff);
  /// The write of `taken` is done: its data still in writeback becomes clean (it may have been
  /// split or moved meanwhile).
  void end_writeback(const Flushed& taken);
  /// Takes every dirty byte of `file` for writing back (fsync), as flush() does.
  std::int64_t flush_file(FileId file, std::vector<Flushed>& out);
  /// Drops every block of `file` (the file is deleted): clean data is freed, dirty data is
  /// discarded. None of it may be in writeback (wait for it first). The policy is told
  /// (Policy::dropped).
  void drop_file(FileId file);
  /// Deletes up to `amount` bytes of clean data, skipping `excluded`, as Policy::reclaim
  /// chooses; `group`: only that group's data, a group other than the root (the kernel's memcg
  /// reclaim, try_to_free_mem_cgroup_pages, scans the group's own lists). Returns how many. Takes no
  /// simulated time.
  std::int64_t evict(std::int64_t amount, FileId excluded, GroupId group = kAnyGroup);
  /// A write of `file` starts (true) or ends (false): a policy may spare files being written.
  void set_being_written(FileId file, bool writing);
  CacheTotals totals() const noexcept { return totals_; }
  /// The walks a policy takes over the lists.
  CacheWalks walks() noexcept { return CacheWalks(*this); }

  /// Throws InvariantError naming the first broken invariant.
  void check_invariants() const;

 private:
  friend class CacheWalks;
  // Figures the operations need, all of them in memory() too.
  std::int64_t cached() const noexcept { return inactive_.bytes() + active_.bytes(); }
  std::int64_t dirty() const noexcept { return inactive_.bytes(BlockState::Dirty) + active_.bytes(BlockState::Dirty); }
  std::int64_t writeback() const noexcept;
  std::int64_t cached(FileId file) const noexcept { return this->file(file).cached(); }
  std::int64_t dirty(FileId file) const noexcept { return file < files_.size() ? files_[file].dirty_bytes : 0; }
  // The walks CacheWalks offers the policies (page_cache_reclaim.cpp, page_cache_walks.cpp).
  std::int64_t evict_clean(ListKind kind, std::int64_t budget, FileId excluded, bool spare_written);
  std::int64_t deactivate_oldest(std::int64_t budget, FileId excluded, bool spare_written);
  BlockId lru_expired(double cutoff);
  void balance();
  /// Evicts front_part(block, bytes), as chosen from the list `from` (Policy::evicted); returns its size.
  std::int64_t evict_front(BlockId block, std::int64_t bytes, ListKind from);
  /// Moves `block` to the MRU end of `to`, its referenced mark set as given.
  void move_to_back(BlockId block, ListKind to, bool referenced);

  void check_after_operation();  // check_invariants(), amortised unless set_checking asked
  // check_invariants' parts (page_cache_check.cpp). `most`: the blocks in use, more steps
  // than which is a cycle.
  std::size_t check_file(std::size_t f, std::size_t most) const;  // returns the file's blocks
  void check_groups() const;
  void check_nodes() const;
  void check_dirty_by_age(std::size_t most) const;
  void check_expiry_scan() const;
  void check_ranges(std::size_t f, std::size_t most) const;

  // A file's lists and counters, in one cache line: with many files an entry is out of cache
  // whenever it is touched.
  using FileOrder = BlockList<&Block::in_file, false>;  // its block count is the entry's
  using FileCleanOrder = BlockList<&Block::state_list, false>;
  struct alignas(64) FileEntry {
    FileOrder inactive;
    FileOrder active;
    // When the policy spares files being written: the file's clean blocks in each LRU list,
    // in LRU order (sub-lists of `inactive` and `active`).
    FileCleanOrder clean_inactive;
    FileCleanOrder clean_active;
    std::int64_t inactive_bytes = 0;
    std::int64_t active_bytes = 0;
    std::int64_t dirty_bytes = 0;
    int writers = 0;            // writes in progress
    std::uint32_t blocks = 0;   // in `inactive` and `active`
  };
  static_assert(sizeof(FileEntry) == 64, "a file's lists and counters fill one cache line");
  using DirtyOrder = BlockList<&Block::state_list, false>;
  using FileWriteback = BlockList<&Block::state_list, false>;  // end_writeback walks these

  FileEntry& file_entry(FileId file);
  LruList& list_of(ListKind kind) noexcept { return kind == ListKind::Inactive ? inactive_ : active_; }
  FileOrder& file_list(FileEntry& entry, ListKind kind) noexcept { return kind == ListKind::Inactive ? entry.inactive : entry.active; }
  FileCleanOrder& file_clean_list(FileEntry& entry, ListKind kind) noexcept {
    return kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
  }
  /// reclaimable_ (heap 0: the host's), or with `by_group` the groups' (heap: GroupId).
  FileHeaps& reclaimable(ListKind kind, bool by_group = false) noexcept {
    return by_group ? groups_.reclaimable(kind) : reclaimable_[static_cast<std::size_t>(kind)];
  }
  /// `file`'s first clean block in `kind` has order `key`: its key lowered there, in both.
  void mark_reclaimable(ListKind kind, FileId file, std::uint64_t key);

  BlockId new_block(FileId file, std::int64_t size, BlockState state, double now, NodeId node);
  /// Adds `bytes` to the clean block at the MRU end of `at.list` if it is the file's with the
  /// same marks; false if there is no such block.
  bool extend_tail(FileId file, std::int64_t bytes, Placement at, NodeId node);
  /// A block of a ranged file holding [offset, offset + size), indexed, on no list yet.
  BlockId new_ranged_block(FileId file, std::int64_t offset, std::int64_t size, BlockState state, double now, NodeId node);
  using Located = FileRanges::Located;
  /// [offset, min(end, its end)) of `block`, which holds `offset`, as a block of its own (cut
  /// off on either side as needed).
  Located cut(Located block, std::int64_t offset, std::int64_t end);
  /// Moves ranged `block`, which starts at `offset`, to the MRU end of `to`, merged into the tail
  /// there if that is clean data of the same file ending at `offset` (same state and mark).
  void move_ranged(BlockId block, std::int64_t offset, ListKind to);
  /// The holes of [offset, end) of a ranged file as new clean data (add_ranged), by offset;
  /// throws SimulationError if one does not fit in free memory. Returns the bytes added.
  /// `first`, if given: FileRanges::at_or_after(file, offset), already looked up.
  /// `demand`: data a read asked for, else data read ahead (Policy::arriving).
  std::int64_t fill_holes(FileId file, std::int64_t offset, std::int64_t end, double now, bool demand, const Located* first = nullptr);
  /// New data of a ranged file, [offset, offset + bytes), at the MRU end of `at.list`: clean
  /// (marked as `at` says) or dirty (entered at `now`). Merged into the tail there if that is
  /// the file's data ending at `offset` in the same state, marks and entry time.
  void add_ranged(FileId file, std::int64_t offset, std::int64_t bytes, BlockState state, double now, Placement at, NodeId node);
  /// add_ranged for new memory: on the nodes NumaNodes::place gives, by offset.
  void place_ranged(FileId file, std::int64_t offset, std::int64_t bytes, BlockState state, double now, Placement at);
  /// Data read from a device, at `offset` of a ranged file (else kNoOffset): where the policy
  /// says (Policy::arriving) if it places arrivals, else inactive, marked if a first touch.
  void add_arriving(FileId file, std::int64_t offset, std::int64_t bytes, double now, bool demand);
  /// Puts one dirty block in writeback under a new token.
  Flushed take_for_writeback(BlockId block);
  /// A dirty block goes into writeback as part of the write `token` (held in its entry time's
  /// place), on its file's list of blocks in writeback.
  void start_writeback(BlockId block, std::uint64_t token);
  /// New data of `file` at the MRU end of `at.list` (dirty data: the inactive list), taken from free memory.
  void add_new(FileId file, std::int64_t bytes, BlockState state, double now, Placement at = {});
  /// add_new's data on one node (its memory already counted as free there, or reserved).
  void add_new_on(NodeId node, FileId file, std::int64_t bytes, BlockState state, double now, Placement at);
  /// The file's inactive block a read resumes at: where `from` left off if that block is still
  /// there, unmoved, else the first.
  BlockId resume_point(const FileEntry& entry, FileId file, ReadCursor from) const noexcept;
  /// reaccess under a policy that rereads in place: each block's bits updated, nothing moved.
  ReadCursor reaccess_in_place(FileId file, std::int64_t bytes, ReadCursor from);
  /// end_writeback's blocks the policy sends to the inactive list's front, in their order.
  void rotate(std::vector<BlockId>& blocks);
  /// evict() by node: each node an equal share of its own data, then the others what it could not.
  std::int64_t evict_by_node(std::int64_t amount, FileId excluded);
  /// Links `block` at the MRU end of `kind` (`front`: at the LRU end) in every list.
  void append(BlockId block, ListKind kind, bool front = false);
  void unlink(BlockId block);
  void destroy(BlockId block);
  void set_state(BlockId block, BlockState state);
  /// Cuts the first `head_size` bytes of `block` off into a new block placed right after it,
  /// in every list, holding the rest; returns `block`, now the head.
  BlockId split_front(BlockId block, std::int64_t head_size);
  /// The first `bytes` (> 0) of `block`, to evict or age, as a block of their own (split_front
  /// unless that is all of it); for a file held by range, up to the next page boundary.
  BlockId front_part(BlockId block, std::int64_t bytes);
  /// On in debug builds, off otherwise; the environment variable PAGECACHE_CHECK_INVARIANTS
  /// (0 or 1) overrides it, e.g. to run large simulations quickly in a debug build.
  static bool checking_by_default();
  /// After a mutation: balance if the policy says so, then check if checking.
  void settle();
  /// The dirty block after `block` in the order flush_expired_block searches: LRU order,
  /// inactive list then active list.
  BlockId next_dirty(BlockId block) const noexcept;
  /// Keeps expiry_scan_ true when a dirty block enters a list or leaves the dirty ones.
  void on_dirty_linked(BlockId block) noexcept;
  void on_dirty_unlinked(BlockId block) noexcept;
  /// Keep the files' clean lists, and reclaimable_, up to date (when the policy spares files
  /// being written): a clean block was linked in its other lists, or a linked block became
  /// clean; a clean block is about to leave its lists or its state.
  void on_clean_linked(BlockId block) { if (index_clean_) link_clean(block); }
  void on_clean_unlinked(BlockId block) { if (index_clean_) unlink_clean(block); }
  void link_clean(BlockId block);
  void unlink_clean(BlockId block);
  /// With the clean index: the least recently used clean block of `kind` in the target group
  /// whose file is neither `excluded` nor being written, or kNoBlock. If `excluded` comes to
  /// the top of its heap it is taken out and `set_aside` set: the caller puts it back.
  BlockId next_unwritten_clean(ListKind kind, FileId excluded, bool& set_aside);

  CacheSettings settings_;
  std::unique_ptr<Policy> policy_;
  // The policy's constant answers, asked once.
  bool index_clean_;     // spares_files_being_written()
  bool first_touch_;     // read_is_first_touch()
  bool balance_always_;  // balance() == AfterEveryChange
  bool balance_reads_;   // balance() != Never
  bool in_place_;        // rereads_in_place()
  bool arrivals_;        // places_arrivals()
  bool rotates_;         // rotates_written_back()
  std::vector<BlockId> rotating_;  // end_writeback's scratch
  std::int64_t total_;
  std::int64_t anonymous_ = 0;
  std::int64_t reserved_ = 0;
  BlockPool blocks_;
  LruList inactive_{ListKind::Inactive, blocks_};
  LruList active_{ListKind::Active, blocks_};
  DirtyOrder dirty_by_age_;  // dirty blocks, oldest entry time first
  // Where the last search for expired data stopped (page_cache_writeback.cpp, lru_expired).
  struct ExpiryScan { BlockId after = kNoBlock; double cutoff = 0.0; };
  ExpiryScan expiry_scan_;
  std::vector<FileEntry> files_;
  std::vector<FileWriteback> writeback_;  // by file, its blocks in writeback (in no order)
  // The files held by byte range (track_ranges) and their blocks' offsets; beside files_: a
  // FileEntry fills its cache line. Empty in a run of whole-file I/O only.
  FileRanges ranges_;
  bool ranged(FileId file) const noexcept { return ranges_.tracked(file); }
  MemoryGroups groups_;
  NumaNodes nodes_;  // empty on a one-node host
  // What the walks take from: one group's data, one node's (kAnyGroup, kAnyNode: all).
  GroupId target_ = kAnyGroup;
  NodeId target_node_ = kAnyNode;  // reclaim's node (evict_by_node)
  bool in_target(const Block& block) const noexcept {
    return (target_ == kAnyGroup || groups_.of(block.file) == target_) && (target_node_ == kAnyNode || block.node == target_node_);
  }
  /// Adds `bytes` to the cached bytes of the file's group and of the node.
  void charge(FileId file, NodeId node, std::int64_t bytes) noexcept {
    groups_.charge(file, bytes);
    if (!nodes_.empty()) nodes_[node].cached += bytes;
  }
  // Per LRU list, with the clean index: the files an eviction sparing the files being written
  // takes from, by first clean block (next_unwritten_clean); each group's are in groups_.
  std::array<FileHeaps, 2> reclaimable_;  // by ListKind
  std::uint64_t next_token_ = 1;
  CacheTotals totals_;
  CacheListeners listeners_;
  bool checking_ = checking_by_default();
  bool amortised_ = checking_;
  std::size_t unchecked_operations_ = 0;
};

/// A node's memory (a one-node host's: the whole).
NodeUse node_use(const PageCache& cache, NodeId node) noexcept;
/// A group's memory, anonymous + cached (on a host without groups, the root's: all of it).
std::int64_t group_usage(const PageCache& cache, GroupId group) noexcept;
/// The data dirty or being written back: what the dirty thresholds limit (as the kernel's
/// balance_dirty_pages counts NR_FILE_DIRTY + NR_WRITEBACK).
std::int64_t dirty_and_writeback(const PageCache& cache) noexcept;
/// What a group may still take before its limit, as far as free memory allows.
std::int64_t group_room(const PageCache& cache, GroupId group) noexcept;

}  // namespace pagecache::cache
