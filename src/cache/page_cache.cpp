#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <cstdlib>
#include <string_view>

namespace pagecache::cache {

bool PageCache::checking_by_default() {
  if (const char* value = std::getenv("PAGECACHE_CHECK_INVARIANTS")) return std::string_view(value) != "0";
#ifdef NDEBUG
  return false;
#else
  return true;
#endif
}

PageCache::PageCache(std::int64_t total_memory, const CacheSettings& settings)
    : settings_(settings), total_(total_memory) {
  if (total_memory <= 0) throw ConfigError(fmt::format("memory size must be > 0, got {} bytes", total_memory));
}

PageCache::~PageCache() = default;

MemoryState PageCache::memory() const noexcept {
  return MemoryState{.total = total_,
                     .free = free(),
                     .anonymous = anonymous_,
                     .cached = cached(),
                     .dirty = dirty(),
                     .writeback = writeback(),
                     .active = active_.bytes(),
                     .inactive = inactive_.bytes(),
                     .reserved = reserved_};
}

std::int64_t PageCache::writeback() const noexcept {
  return inactive_.bytes(BlockState::Writeback) + active_.bytes(BlockState::Writeback);
}

std::int64_t PageCache::dirtyable() const noexcept {
  // Copies into the cache in flight (reserved) are file pages already, as the kernel's pages
  // are dirtied one by one while the copy runs.
  return settings_.dirtyable_memory ? free() + cached() + reserved_ : free() + cached() - dirty() - writeback();
}

std::int64_t PageCache::dirty_and_writeback() const noexcept { return dirty() + writeback(); }

PageCache::DirtyLimits PageCache::dirty_limits() const noexcept {
  const double base = static_cast<double>(std::max<std::int64_t>(dirtyable(), 0));
  DirtyLimits l;
  l.thresh = static_cast<std::int64_t>(settings_.dirty_ratio * base);
  l.background = settings_.dirty_background_ratio < settings_.dirty_ratio
                     ? static_cast<std::int64_t>(settings_.dirty_background_ratio * base)
                     : l.thresh / 2;
  l.freerun = (l.background + l.thresh) / 2;
  return l;
}

std::int64_t PageCache::evictable() const noexcept {
  return settings_.reclaim_inactive_only ? inactive_.bytes(BlockState::Clean) : inactive_.bytes();
}

void PageCache::allocate_anonymous(std::int64_t bytes) {
  PC_ASSERT(bytes >= 0);
  if (bytes > free()) {
    throw SimulationError(fmt::format("out of memory: {} bytes of application memory requested, {} free", bytes, free()));
  }
  anonymous_ += bytes;
  settle();
}

void PageCache::release_anonymous(std::int64_t bytes) {
  PC_ASSERT(bytes >= 0 && bytes <= anonymous_);
  anonymous_ -= bytes;
  settle();
  if (progress_hook_) progress_hook_();
}

// --- Per file -------------------------------------------------------------------------------

PageCache::FileEntry& PageCache::file_entry(FileId file) {
  PC_ASSERT(file != kNoFile);
  if (file >= files_.size()) files_.resize(static_cast<std::size_t>(file) + 1);
  return files_[file];
}

std::int64_t PageCache::cached(FileId file) const noexcept {
  if (file >= files_.size()) return 0;
  return files_[file].inactive_bytes + files_[file].active_bytes;
}

std::int64_t PageCache::cached(FileId file, ListKind kind) const noexcept {
  if (file >= files_.size()) return 0;
  return kind == ListKind::Inactive ? files_[file].inactive_bytes : files_[file].active_bytes;
}

std::int64_t PageCache::dirty(FileId file) const noexcept {
  return file < files_.size() ? files_[file].dirty_bytes : 0;
}

// --- Block bookkeeping: every list and counter changes here and only here -------------------

BlockId PageCache::new_block(FileId file, std::int64_t size, BlockState state, double now) {
  const BlockId id = blocks_.take();
  Block& block = blocks_[id];
  block.file = file;
  block.size = size;
  block.state = state;
  block.entry_time = now;
  return id;
}

void PageCache::append(BlockId id, ListKind kind) {
  const Block& block = blocks_[id];
  FileEntry& entry = file_entry(block.file);
  list_of(kind).push_back(id);
  on_dirty_linked(id);
  file_list(entry, kind).push_back(blocks_, id);
  ++entry.blocks;
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += block.size;
  if (block.state == BlockState::Dirty) entry.dirty_bytes += block.size;
  if (block.state == BlockState::Clean) on_clean_linked(id);
}

void PageCache::unlink(BlockId id) {
  const Block& block = blocks_[id];
  FileEntry& entry = files_[block.file];
  on_dirty_unlinked(id);
  if (block.state == BlockState::Clean) on_clean_unlinked(id);
  list_of(block.list).erase(id);
  file_list(entry, block.list).erase(blocks_, id);
  --entry.blocks;
  (block.list == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) -= block.size;
  if (block.state == BlockState::Dirty) entry.dirty_bytes -= block.size;
}

bool PageCache::extend_tail(ListKind kind, FileId file, std::int64_t bytes, bool referenced) {
  // New clean data of the file at the most recently used end, right behind a clean block of
  // the same file in the same state: one block, not two. The bytes are in the same place on
  // the lists either way; a file read chunk by chunk then holds a block per run, not per
  // chunk, which bounds the number of blocks by the runs of data rather than the chunks.
  LruList& list = list_of(kind);
  const BlockId tail_id = list.back();
  if (tail_id == kNoBlock) return false;
  const Block& tail = blocks_[tail_id];
  if (tail.file != file || tail.state != BlockState::Clean || tail.referenced != referenced) return false;
  list.resize(tail_id, tail.size + bytes);
  FileEntry& entry = files_[file];
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += bytes;
  return true;
}

void PageCache::destroy(BlockId id) {
  unlink(id);
  if (blocks_[id].state == BlockState::Dirty) dirty_by_age_.erase(blocks_, id);
  blocks_.give_back(id);
}

void PageCache::set_state(BlockId id, BlockState state) {
  Block& block = blocks_[id];
  // Data becomes dirty only as a new block (add_new): its place by age is the newest.
  PC_ASSERT(state != BlockState::Dirty || block.state == BlockState::Dirty);
  if (block.state == BlockState::Dirty && state != BlockState::Dirty) {
    dirty_by_age_.erase(blocks_, id);
    on_dirty_unlinked(id);
  }
  FileEntry& entry = files_[block.file];
  if (block.state == BlockState::Dirty) entry.dirty_bytes -= block.size;
  if (state == BlockState::Dirty) entry.dirty_bytes += block.size;
  const bool was_clean = block.state == BlockState::Clean;
  if (was_clean && state != BlockState::Clean) on_clean_unlinked(id);
  // Out of writeback, the bytes that held its write are its links again.
  if (block.state == BlockState::Writeback && state != BlockState::Writeback) block.dirty_or_clean = BlockLinks{};
  list_of(block.list).set_state(id, state);
  if (!was_clean && state == BlockState::Clean) on_clean_linked(id);
}

void PageCache::start_writeback(BlockId id, std::uint64_t token) {
  set_state(id, BlockState::Writeback);
  blocks_[id].writeback_batch = token;  // off the dirty and clean lists: their links are free
}

void PageCache::link_clean(BlockId id) {
  const Block& block = blocks_[id];
  FileEntry& entry = files_[block.file];
  FileCleanOrder& clean = file_clean_list(entry, block.list);
  link_in_order(blocks_, file_list(entry, block.list), clean, id, [](const Block& b) { return b.state == BlockState::Clean; });
  // A higher key waits until the file comes to the top of reclaimable_ (see there).
  if (clean.front() == id && entry.writers == 0) reclaimable(block.list).lower(block.file, block.order);
}

void PageCache::unlink_clean(BlockId id) {
  const Block& block = blocks_[id];
  file_clean_list(files_[block.file], block.list).erase(blocks_, id);
}

BlockId PageCache::split_front(BlockId id, std::int64_t head_size) {
  const BlockId tail_id = blocks_.take();
  Block& block = blocks_[id];
  Block& tail = blocks_[tail_id];
  PC_ASSERT(head_size > 0 && head_size < block.size);
  tail.file = block.file;
  tail.size = block.size - head_size;
  tail.state = block.state;
  tail.entry_time = block.entry_time;
  tail.referenced = block.referenced;
  if (block.state == BlockState::Writeback) tail.writeback_batch = block.writeback_batch;
  LruList& list = list_of(block.list);
  list.resize(id, head_size);
  list.insert_after(id, tail_id);
  on_dirty_linked(tail_id);
  FileEntry& entry = files_[block.file];
  file_list(entry, block.list).insert_after(blocks_, id, tail_id);
  ++entry.blocks;
  if (tail.state == BlockState::Dirty) dirty_by_age_.insert_after(blocks_, id, tail_id);
  if (tail.state == BlockState::Clean && settings_.protect_files_being_written) {
    file_clean_list(entry, block.list).insert_after(blocks_, id, tail_id);
  }
  // Per-file byte counters are unchanged: the file holds the same bytes in the same list.
  return id;
}

void PageCache::settle() {
  if (settings_.balance_after_every_change) balance();
  if (checking_) check_invariants();
  if (observer_) observer_();
}

// --- Cache contents -------------------------------------------------------------------------

void PageCache::add_new(FileId file, std::int64_t bytes, BlockState state, double now, bool referenced) {
  PC_ASSERT(bytes >= 0);
  if (bytes == 0) return;
  if (bytes > free()) {
    throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", bytes, free()));
  }
  if (state == BlockState::Clean && extend_tail(ListKind::Inactive, file, bytes, referenced)) {
    settle();
    return;
  }
  const BlockId id = new_block(file, bytes, state, now);
  blocks_[id].referenced = referenced;
  append(id, ListKind::Inactive);
  if (state == BlockState::Dirty) {
    // Its place by age: the newest in a simulation, where time only goes forward; callers
    // that pass earlier times (tests) get it sorted in.
    BlockId after = dirty_by_age_.back();
    while (after != kNoBlock && blocks_[after].entry_time > now) after = DirtyOrder::prev(blocks_, after);
    if (after == kNoBlock) dirty_by_age_.push_front(blocks_, id);
    else dirty_by_age_.insert_after(blocks_, after, id);
  }
  settle();
}

void PageCache::add_clean(FileId file, std::int64_t bytes, double now) { add_new(file, bytes, BlockState::Clean, now); }

void PageCache::add_read(FileId file, std::int64_t bytes, double now) {
  // The read that brought the data in is its first touch.
  add_new(file, bytes, BlockState::Clean, now, settings_.two_touch_activation);
}

void PageCache::add_dirty(FileId file, std::int64_t bytes, double now) {
  add_new(file, bytes, BlockState::Dirty, now);
  peak_dirty_ = std::max(peak_dirty_, dirty());
}

void PageCache::reserve(std::int64_t bytes) {
  PC_ASSERT(bytes >= 0);
  if (bytes > free()) throw SimulationError(fmt::format("cannot reserve {} bytes: only {} free", bytes, free()));
  reserved_ += bytes;
  settle();
}

void PageCache::commit_dirty(FileId file, std::int64_t bytes, double now) {
  PC_ASSERT(bytes >= 0 && bytes <= reserved_);
  reserved_ -= bytes;
  add_dirty(file, bytes, now);
  if (progress_hook_) progress_hook_();
}

void PageCache::reaccess(FileId file, std::int64_t bytes, double now) {
  PC_ASSERT(bytes >= 0 && bytes <= cached(file));
  FileEntry& entry = file_entry(file);
  std::int64_t left = bytes;
  std::int64_t merged_clean = 0;
  // Activation: clean data read is merged into one new block; dirty (or writeback) data moves
  // on its own, keeping its entry time.
  auto activate = [&](BlockId id) {
    Block& block = blocks_[id];
    if (block.state == BlockState::Clean) {
      merged_clean += block.size;
      destroy(id);
    } else {
      unlink(id);
      block.referenced = false;
      append(id, ListKind::Active);
    }
  };
  // Inactive blocks, least recently used first. With two-touch activation, a block read for
  // the first time since it entered the cache is only marked referenced and stays in place
  // (mark_page_accessed); read again, it is activated.
  BlockId at = entry.inactive.front();
  while (left > 0 && at != kNoBlock) {
    const BlockId id = blocks_[at].size > left ? split_front(at, left) : at;
    at = FileOrder::next(blocks_, id);
    Block& block = blocks_[id];
    left -= block.size;
    if (settings_.two_touch_activation && !block.referenced) {
      block.referenced = true;
      continue;
    }
    activate(id);
  }
  // Active blocks: taken from the front of the file's active list and moved to the back, so
  // that none is met twice.
  while (left > 0 && !entry.active.empty()) {
    const BlockId front = entry.active.front();
    const BlockId id = blocks_[front].size > left ? split_front(front, left) : front;
    left -= blocks_[id].size;
    activate(id);
  }
  PC_ASSERT(left == 0);
  if (merged_clean > 0 && !extend_tail(ListKind::Active, file, merged_clean, false)) {
    append(new_block(file, merged_clean, BlockState::Clean, now), ListKind::Active);
  }
  balance();  // after every read, in both profiles
  settle();
}

std::int64_t PageCache::flush(std::int64_t amount, FileId excluded, std::vector<Flushed>& out) {
  std::int64_t flushed = 0;
  const std::uint64_t token = next_token_++;
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    LruList& list = list_of(kind);
    BlockId id = list.front(BlockState::Dirty);
    while (id != kNoBlock && flushed < amount) {
      const BlockId next = list.next_in_state(id);
      if (blocks_[id].file != excluded) {
        const bool partial = blocks_[id].size > amount - flushed;
        const BlockId target = partial ? split_front(id, amount - flushed) : id;
        const Block& block = blocks_[target];
        flushed += block.size;
        if (!out.empty() && out.back().file == block.file && out.back().token == token) out.back().bytes += block.size;
        else out.push_back({block.file, block.size, token});
        start_writeback(target, token);
        if (partial && !settings_.flush_splits_in_place) {
          // WRENCH-cache moves the flushed part of a split block to the MRU end of the
          // inactive list.
          unlink(target);
          append(target, ListKind::Inactive);
        }
      }
      id = next;
    }
  }
  settle();
  return flushed;
}

std::int64_t PageCache::flush_file(FileId file, std::vector<Flushed>& out) {
  std::int64_t flushed = 0;
  const std::uint64_t token = next_token_++;
  FileEntry& entry = file_entry(file);
  for (FileOrder* flist : {&entry.inactive, &entry.active}) {
    for (BlockId id = flist->front(); id != kNoBlock; id = FileOrder::next(blocks_, id)) {
      if (blocks_[id].state != BlockState::Dirty) continue;
      flushed += blocks_[id].size;
      start_writeback(id, token);
    }
  }
  if (flushed > 0) out.push_back({file, flushed, token});
  settle();
  return flushed;
}

std::int64_t PageCache::writeback(FileId file) const noexcept {
  if (file >= files_.size()) return 0;
  std::int64_t bytes = 0;
  for (const FileOrder* flist : {&files_[file].inactive, &files_[file].active}) {
    for (const Block& block : flist->range(blocks_)) {
      if (block.state == BlockState::Writeback) bytes += block.size;
    }
  }
  return bytes;
}

void PageCache::drop_file(FileId file) {
  FileEntry& entry = file_entry(file);
  for (FileOrder* flist : {&entry.inactive, &entry.active}) {
    while (!flist->empty()) {
      const BlockId id = flist->front();
      PC_ASSERT_MSG(blocks_[id].state != BlockState::Writeback, "a file is dropped while being written back");
      destroy(id);
    }
  }
  settle();
  if (progress_hook_) progress_hook_();
}

PageCache::Flushed PageCache::take_for_writeback(BlockId id) {
  const Flushed taken{blocks_[id].file, blocks_[id].size, next_token_++};
  start_writeback(id, taken.token);
  settle();
  return taken;
}

PageCache::Flushed PageCache::flush_expired_block(double cutoff) {
  // Nothing expired if the oldest dirty data has not: O(1) for the flusher's usual tick.
  if (dirty_by_age_.empty() || blocks_[dirty_by_age_.front()].entry_time > cutoff) return {kNoFile, 0};
  if (settings_.expire_oldest_first) return take_for_writeback(dirty_by_age_.front());
  // The least recently used expired block, inactive list first; a search under the cutoff of
  // the previous one resumes where that one stopped.
  BlockId id = kNoBlock;
  if (expiry_scan_.after != kNoBlock && expiry_scan_.cutoff == cutoff) {
    id = next_dirty(expiry_scan_.after);
  } else {
    expiry_scan_ = {};
    id = inactive_.front(BlockState::Dirty);
    if (id == kNoBlock) id = active_.front(BlockState::Dirty);
  }
  for (; id != kNoBlock; id = next_dirty(id)) {
    if (blocks_[id].entry_time <= cutoff) return take_for_writeback(id);
    expiry_scan_ = {id, cutoff};
  }
  return {kNoFile, 0};
}

BlockId PageCache::next_dirty(BlockId id) const noexcept {
  const Block& block = blocks_[id];
  BlockId next = (block.list == ListKind::Inactive ? inactive_ : active_).next_in_state(id);
  if (next == kNoBlock && block.list == ListKind::Inactive) next = active_.front(BlockState::Dirty);
  return next;
}

void PageCache::on_dirty_linked(BlockId id) noexcept {
  const Block& block = blocks_[id];
  if (expiry_scan_.after != kNoBlock && block.state == BlockState::Dirty && block.entry_time <= expiry_scan_.cutoff) {
    expiry_scan_ = {};
  }
}

void PageCache::on_dirty_unlinked(BlockId id) noexcept {
  if (id == expiry_scan_.after) expiry_scan_ = {};
}

void PageCache::end_writeback(const Flushed& taken) {
  if (taken.bytes == 0) return;
  // The blocks of one write carry its token (splits pass it on) and all belong to its file.
  // They are looked for among the file's blocks or among all blocks in writeback, whichever
  // are fewer: the file's when many writes are in flight at once (many writers flushing), the
  // blocks in writeback when one file holds many blocks. Both visit the blocks in LRU order,
  // inactive list first, so the lists end up the same either way.
  auto end = [&](BlockId id) {
    const Block& block = blocks_[id];
    if (block.state != BlockState::Writeback || block.writeback_batch != taken.token) return;
    set_state(id, BlockState::Clean);
  };
  FileEntry& entry = files_[taken.file];
  const std::size_t in_writeback = inactive_.blocks_in(BlockState::Writeback) + active_.blocks_in(BlockState::Writeback);
  if (entry.blocks <= in_writeback) {
    for (FileOrder* flist : {&entry.inactive, &entry.active}) {
      for (BlockId id = flist->front(); id != kNoBlock; id = FileOrder::next(blocks_, id)) end(id);
    }
  } else {
    for (LruList* list : {&inactive_, &active_}) {
      BlockId id = list->front(BlockState::Writeback);
      while (id != kNoBlock) {
        const BlockId next = list->next_in_state(id);
        end(id);
        id = next;
      }
    }
  }
  settle();
  if (progress_hook_) progress_hook_();
}

std::int64_t PageCache::evict(std::int64_t amount, FileId excluded) {
  std::int64_t evicted = 0;
  auto take = [&](BlockId id) {
    const BlockId victim = blocks_[id].size > amount - evicted ? split_front(id, amount - evicted) : id;
    evicted += blocks_[victim].size;
    evicted_total_ += blocks_[victim].size;
    destroy(victim);
  };
  // One reclaim pass; `spare_written` also skips the files open for writing.
  auto pass = [&](bool spare_written) {
    auto spared = [&](BlockId id) {
      const FileId file = blocks_[id].file;
      return file == excluded || (spare_written && files_[file].writers > 0);
    };
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      if (kind == ListKind::Active && settings_.reclaim_inactive_only) break;
      if (spare_written) {
        // The same victims in the same order as the walk below, without walking past the
        // clean blocks of the files being written.
        bool set_aside = false;
        while (evicted < amount) {
          const BlockId victim = next_unwritten_clean(kind, excluded, set_aside);
          if (victim == kNoBlock) break;
          take(victim);
        }
        // Only other files' blocks were taken: the excluded file's first clean block is the same.
        if (set_aside) reclaimable(kind).lower(excluded, blocks_[file_clean_list(files_[excluded], kind).front()].order);
        continue;
      }
      LruList& list = list_of(kind);
      BlockId id = list.front(BlockState::Clean);
      while (id != kNoBlock && evicted < amount) {
        const BlockId next = list.next_in_state(id);
        if (!spared(id)) take(id);
        id = next;
      }
    }
    if (settings_.reclaim_inactive_only) {
      // Active list aging (mm/vmscan.c, shrink_active_list): with no clean inactive data left,
      // the oldest active data is deactivated, and reclaimed if it is clean.
      while (evicted < amount && !active_.empty()) {
        const BlockId oldest = active_.front();
        unlink(oldest);
        blocks_[oldest].referenced = false;
        append(oldest, ListKind::Inactive);
        if (blocks_[oldest].state == BlockState::Clean && !spared(oldest)) take(oldest);
      }
    }
  };
  pass(settings_.protect_files_being_written);
  if (evicted < amount && settings_.protect_files_being_written) pass(false);
  settle();
  tracer_.eviction(evicted);
  return evicted;
}

BlockId PageCache::next_unwritten_clean(ListKind kind, FileId excluded, bool& set_aside) {
  // The least recently used clean block, unless spared; if it is, the first clean block of
  // the top file of reclaimable_, once the top's key is that block's.
  const BlockId front = list_of(kind).front(BlockState::Clean);
  if (front == kNoBlock) return kNoBlock;
  const FileId front_file = blocks_[front].file;
  if (front_file != excluded && files_[front_file].writers == 0) return front;
  FileHeap& files = reclaimable(kind);
  while (!files.empty()) {
    const FileHeap::Entry top = files.top();
    FileEntry& entry = files_[top.file];
    FileCleanOrder& clean = file_clean_list(entry, kind);
    if (clean.empty() || entry.writers > 0) {
      files.pop();
    } else if (blocks_[clean.front()].order != top.key) {
      files.raise_top(blocks_[clean.front()].order);
    } else if (top.file == excluded) {
      files.pop();
      set_aside = true;
    } else {
      return clean.front();
    }
  }
  return kNoBlock;
}

void PageCache::set_being_written(FileId file, bool writing) {
  FileEntry& entry = file_entry(file);
  const bool was_written = entry.writers > 0;
  entry.writers += writing ? 1 : -1;
  PC_ASSERT(entry.writers >= 0);
  if (!settings_.protect_files_being_written || was_written == (entry.writers > 0)) return;
  // Its last write ended: the file is among those eviction may take from while sparing the
  // files being written. (Its first write started: it leaves them when it comes to the top.)
  if (!writing) {
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      const FileCleanOrder& clean = file_clean_list(entry, kind);
      if (!clean.empty()) reclaimable(kind).lower(file, blocks_[clean.front()].order);
    }
  }
  if (checking_) check_invariants();
}

void PageCache::balance() {
  const std::int64_t excess = active_.bytes() - 2 * inactive_.bytes();
  if (excess <= 0) return;
  // Moving x bytes leaves active - x <= 2 (inactive + x): x >= excess / 3, rounded up.
  std::int64_t to_move = (excess + 2) / 3;
  while (to_move > 0) {
    const BlockId front = active_.front();
    PC_ASSERT(front != kNoBlock);
    const BlockId id = blocks_[front].size > to_move ? split_front(front, to_move) : front;
    to_move -= blocks_[id].size;
    unlink(id);
    blocks_[id].referenced = false;
    append(id, ListKind::Inactive);
  }
}

void PageCache::check_invariants() const {
  inactive_.check();
  active_.check();
  PC_ASSERT_MSG(anonymous_ >= 0, fmt::format("anonymous {} < 0", anonymous_));
  PC_ASSERT_MSG(free() >= 0, fmt::format("free {} < 0 (total {}, anonymous {}, cached {}, reserved {})", free(), total_,
                                          anonymous_, cached(), reserved_));
  PC_ASSERT(reserved_ >= 0);
  PC_ASSERT(dirty() >= 0 && dirty() + writeback() <= cached());
  PC_ASSERT(blocks_.in_use() == inactive_.size() + active_.size());
  // Every walk below meets each block at most once: more steps than blocks is a cycle.
  const std::size_t most = blocks_.in_use();
  std::size_t blocks_in_files = 0;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    const FileEntry& entry = files_[f];
    std::int64_t bytes[2] = {0, 0};
    std::int64_t dirty_bytes = 0;
    std::size_t blocks = 0;
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      const FileOrder& flist = kind == ListKind::Inactive ? entry.inactive : entry.active;
      // Its clean list holds its clean blocks in the list, in order; and its place in
      // reclaimable_.
      const FileCleanOrder& clean = kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
      auto clean_it = clean.range(blocks_).begin();
      const auto clean_end = clean.range(blocks_).end();
      if (settings_.protect_files_being_written) {
        for (const Block& b : flist.range(blocks_)) {
          if (b.state != BlockState::Clean) continue;
          PC_ASSERT_MSG(clean_it != clean_end && &*clean_it == &b, fmt::format("file {}: clean list out of order", f));
          ++clean_it;
        }
      }
      PC_ASSERT_MSG(clean_it == clean_end, fmt::format("file {}: a block on its clean list in error", f));
      if (!clean.empty() && entry.writers == 0) {
        const FileHeap& files = reclaimable_[static_cast<std::size_t>(kind)];
        const auto file = static_cast<FileId>(f);
        PC_ASSERT_MSG(files.contains(file) && files.key(file) <= blocks_[clean.front()].order,
                      fmt::format("file {} missing from the reclaimable files, or its key too high", f));
      }
      // The file's list follows the LRU list's order.
      const auto lru = list(kind).blocks();
      auto lru_it = lru.begin();
      for (const Block& b : flist.range(blocks_)) {
        PC_ASSERT_MSG(blocks < most, fmt::format("file {}: its lists hold more blocks than there are (a cycle?)", f));
        PC_ASSERT_MSG(b.file == f && b.list == kind, "block on the wrong file or list");
        while (lru_it != lru.end() && &*lru_it != &b) ++lru_it;
        PC_ASSERT_MSG(lru_it != lru.end(), "file list out of LRU order");
        bytes[static_cast<int>(kind)] += b.size;
        if (b.state == BlockState::Dirty) dirty_bytes += b.size;
        ++blocks;
      }
    }
    PC_ASSERT_MSG(bytes[0] == entry.inactive_bytes && bytes[1] == entry.active_bytes,
                  fmt::format("file {} byte counters disagree with its blocks", f));
    PC_ASSERT(dirty_bytes == entry.dirty_bytes);
    PC_ASSERT_MSG(entry.blocks == blocks, fmt::format("file {}: block count disagrees with its lists", f));
    blocks_in_files += blocks;
  }
  PC_ASSERT_MSG(blocks_in_files == inactive_.size() + active_.size(), "a block is missing from its file's list");
  for (const FileHeap& files : reclaimable_) {
    files.check();
    PC_ASSERT(settings_.protect_files_being_written || files.empty());
  }
  std::size_t dirty_blocks = 0;
  double previous = -std::numeric_limits<double>::infinity();
  for (const Block& b : dirty_by_age_.range(blocks_)) {
    PC_ASSERT_MSG(dirty_blocks < most, "the list by age holds more blocks than there are (a cycle?)");
    PC_ASSERT_MSG(b.state == BlockState::Dirty, "a block on the list by age is not dirty");
    PC_ASSERT_MSG(b.entry_time >= previous, "dirty blocks out of age order");
    previous = b.entry_time;
    ++dirty_blocks;
  }
  PC_ASSERT_MSG(dirty_blocks == inactive_.blocks_in(BlockState::Dirty) + active_.blocks_in(BlockState::Dirty),
                "a dirty block is missing from the list by age");
  if (expiry_scan_.after != kNoBlock) {
    const Block& after = blocks_[expiry_scan_.after];
    PC_ASSERT_MSG(after.state == BlockState::Dirty, "the expiry search stopped at a block no longer dirty");
    bool reached = false;
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      for (const Block& b : list(kind).blocks()) {
        if (&b == &after) reached = true;
        if (reached) break;
        PC_ASSERT_MSG(b.state != BlockState::Dirty || b.entry_time > expiry_scan_.cutoff,
                      "an expired block lies before where the expiry search resumes");
      }
      if (reached) break;
    }
    PC_ASSERT_MSG(reached, "the expiry search stopped at a block not in the lists");
  }
}

}  // namespace pagecache::cache
