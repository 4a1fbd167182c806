#include "cache/page_cache.hpp"

#include "cache/sub_list.hpp"
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

PageCache::~PageCache() {
  for (LruList* list : {&inactive_, &active_}) {
    while (Block* block = list->front()) destroy(*block);
  }
}

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

Block& PageCache::new_block(FileId file, std::int64_t size, BlockState state, double now) {
  Block* block = pool_.take();
  block->file = file;
  block->size = size;
  block->state = state;
  block->last_access = now;
  block->entry_time = now;
  return *block;
}

void PageCache::append(Block& block, ListKind kind) {
  FileEntry& entry = file_entry(block.file);
  list_of(kind).push_back(block);
  on_dirty_linked(block);
  file_list(entry, kind).push_back(block);
  ++entry.blocks;
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += block.size;
  if (block.state == BlockState::Dirty) entry.dirty_bytes += block.size;
  if (block.state == BlockState::Clean) on_clean_linked(block);
}

void PageCache::unlink(Block& block) {
  FileEntry& entry = files_[block.file];
  on_dirty_unlinked(block);
  if (block.state == BlockState::Clean) on_clean_unlinked(block);
  list_of(block.list).erase(block);
  FileOrder& flist = file_list(entry, block.list);
  flist.erase(flist.iterator_to(block));
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
  Block* tail = list.back();
  if (tail == nullptr || tail->file != file || tail->state != BlockState::Clean || tail->referenced != referenced) return false;
  list.resize(*tail, tail->size + bytes);
  FileEntry& entry = files_[file];
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += bytes;
  return true;
}

void PageCache::destroy(Block& block) {
  unlink(block);
  if (block.state == BlockState::Dirty) dirty_by_age_.erase(dirty_by_age_.iterator_to(block));
  pool_.give_back(&block);
}

void PageCache::set_state(Block& block, BlockState state) {
  // Data becomes dirty only as a new block (add_new): its place by age is the newest.
  PC_ASSERT(state != BlockState::Dirty || block.state == BlockState::Dirty);
  if (block.state == BlockState::Dirty && state != BlockState::Dirty) {
    dirty_by_age_.erase(dirty_by_age_.iterator_to(block));
    on_dirty_unlinked(block);
  }
  FileEntry& entry = files_[block.file];
  if (block.state == BlockState::Dirty) entry.dirty_bytes -= block.size;
  if (state == BlockState::Dirty) entry.dirty_bytes += block.size;
  const bool was_clean = block.state == BlockState::Clean;
  if (was_clean && state != BlockState::Clean) on_clean_unlinked(block);
  list_of(block.list).set_state(block, state);
  if (!was_clean && state == BlockState::Clean) on_clean_linked(block);
}

void PageCache::link_clean(Block& block) {
  FileEntry& entry = files_[block.file];
  FileCleanOrder& clean = file_clean_list(entry, block.list);
  link_in_order(file_list(entry, block.list), clean, block, [](const Block& b) { return b.state == BlockState::Clean; });
  // A higher key waits until the file comes to the top of reclaimable_ (see there).
  if (&clean.front() == &block && entry.writers == 0) reclaimable(block.list).lower(block.file, block.order);
}

void PageCache::unlink_clean(Block& block) {
  FileCleanOrder& clean = file_clean_list(files_[block.file], block.list);
  clean.erase(clean.iterator_to(block));
}

Block& PageCache::split_front(Block& block, std::int64_t head_size) {
  PC_ASSERT(head_size > 0 && head_size < block.size);
  Block& tail = *pool_.take();
  tail.file = block.file;
  tail.size = block.size - head_size;
  tail.state = block.state;
  tail.last_access = block.last_access;
  tail.entry_time = block.entry_time;
  tail.referenced = block.referenced;
  tail.writeback_batch = block.writeback_batch;
  LruList& list = list_of(block.list);
  list.resize(block, head_size);
  list.insert_after(block, tail);
  on_dirty_linked(tail);
  FileEntry& entry = files_[block.file];
  FileOrder& flist = file_list(entry, block.list);
  flist.insert(std::next(flist.iterator_to(block)), tail);
  ++entry.blocks;
  if (tail.state == BlockState::Dirty) dirty_by_age_.insert(std::next(dirty_by_age_.iterator_to(block)), tail);
  if (tail.state == BlockState::Clean && settings_.protect_files_being_written) {
    FileCleanOrder& clean = file_clean_list(entry, block.list);
    clean.insert(std::next(clean.iterator_to(block)), tail);
  }
  // Per-file byte counters are unchanged: the file holds the same bytes in the same list.
  return block;
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
  Block& block = new_block(file, bytes, state, now);
  block.referenced = referenced;
  append(block, ListKind::Inactive);
  if (state == BlockState::Dirty) {
    // Its place by age: the newest in a simulation, where time only goes forward; callers
    // that pass earlier times (tests) get it sorted in.
    auto at = dirty_by_age_.end();
    while (at != dirty_by_age_.begin() && std::prev(at)->entry_time > now) --at;
    dirty_by_age_.insert(at, block);
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
  auto activate = [&](Block& block) {
    if (block.state == BlockState::Clean) {
      merged_clean += block.size;
      destroy(block);
    } else {
      unlink(block);
      block.referenced = false;
      append(block, ListKind::Active);
    }
  };
  // Inactive blocks, least recently used first. With two-touch activation, a block read for
  // the first time since it entered the cache is only marked referenced and stays in place
  // (mark_page_accessed); read again, it is activated.
  auto it = entry.inactive.begin();
  while (left > 0 && it != entry.inactive.end()) {
    Block& front = *it;
    Block& block = front.size > left ? split_front(front, left) : front;
    ++it;
    left -= block.size;
    if (settings_.two_touch_activation && !block.referenced) {
      block.referenced = true;
      continue;
    }
    activate(block);
  }
  // Active blocks: taken from the front of the file's active list and moved to the back, so
  // that none is met twice.
  while (left > 0 && !entry.active.empty()) {
    Block& front = entry.active.front();
    Block& block = front.size > left ? split_front(front, left) : front;
    left -= block.size;
    activate(block);
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
    Block* block = list.front(BlockState::Dirty);
    while (block != nullptr && flushed < amount) {
      Block* next = list.next(*block, BlockState::Dirty);
      if (block->file != excluded) {
        const bool partial = block->size > amount - flushed;
        Block& target = partial ? split_front(*block, amount - flushed) : *block;
        flushed += target.size;
        if (!out.empty() && out.back().file == target.file && out.back().token == token) out.back().bytes += target.size;
        else out.push_back({target.file, target.size, token});
        target.writeback_batch = token;
        set_state(target, BlockState::Writeback);
        if (partial && !settings_.flush_splits_in_place) {
          // WRENCH-cache moves the flushed part of a split block to the MRU end of the
          // inactive list.
          unlink(target);
          append(target, ListKind::Inactive);
        }
      }
      block = next;
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
    for (Block& block : *flist) {
      if (block.state != BlockState::Dirty) continue;
      block.writeback_batch = token;
      flushed += block.size;
      set_state(block, BlockState::Writeback);
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
    for (const Block& block : *flist) {
      if (block.state == BlockState::Writeback) bytes += block.size;
    }
  }
  return bytes;
}

void PageCache::drop_file(FileId file) {
  FileEntry& entry = file_entry(file);
  for (FileOrder* flist : {&entry.inactive, &entry.active}) {
    while (!flist->empty()) {
      Block& block = flist->front();
      PC_ASSERT_MSG(block.state != BlockState::Writeback, "a file is dropped while being written back");
      destroy(block);
    }
  }
  settle();
  if (progress_hook_) progress_hook_();
}

PageCache::Flushed PageCache::take_for_writeback(Block& block) {
  const Flushed taken{block.file, block.size, next_token_++};
  block.writeback_batch = taken.token;
  set_state(block, BlockState::Writeback);
  settle();
  return taken;
}

PageCache::Flushed PageCache::flush_expired_block(double cutoff) {
  // Nothing expired if the oldest dirty data has not: O(1) for the flusher's usual tick.
  if (dirty_by_age_.empty() || dirty_by_age_.front().entry_time > cutoff) return {kNoFile, 0};
  if (settings_.expire_oldest_first) return take_for_writeback(dirty_by_age_.front());
  // The least recently used expired block, inactive list first; a search under the cutoff of
  // the previous one resumes where that one stopped.
  Block* block = nullptr;
  if (expiry_scan_.after != nullptr && expiry_scan_.cutoff == cutoff) {
    block = next_dirty(*expiry_scan_.after);
  } else {
    expiry_scan_ = {};
    block = inactive_.front(BlockState::Dirty);
    if (block == nullptr) block = active_.front(BlockState::Dirty);
  }
  for (; block != nullptr; block = next_dirty(*block)) {
    if (block->entry_time <= cutoff) return take_for_writeback(*block);
    expiry_scan_ = {block, cutoff};
  }
  return {kNoFile, 0};
}

Block* PageCache::next_dirty(Block& block) noexcept {
  Block* next = list_of(block.list).next(block, BlockState::Dirty);
  if (next == nullptr && block.list == ListKind::Inactive) next = active_.front(BlockState::Dirty);
  return next;
}

void PageCache::on_dirty_linked(const Block& block) noexcept {
  if (expiry_scan_.after != nullptr && block.state == BlockState::Dirty && block.entry_time <= expiry_scan_.cutoff) {
    expiry_scan_ = {};
  }
}

void PageCache::on_dirty_unlinked(const Block& block) noexcept {
  if (&block == expiry_scan_.after) expiry_scan_ = {};
}

void PageCache::end_writeback(const Flushed& taken) {
  if (taken.bytes == 0) return;
  // The blocks of one write carry its token (splits pass it on) and all belong to its file.
  // They are looked for among the file's blocks or among all blocks in writeback, whichever
  // are fewer: the file's when many writes are in flight at once (many writers flushing), the
  // blocks in writeback when one file holds many blocks. Both visit the blocks in LRU order,
  // inactive list first, so the lists end up the same either way.
  auto end = [&](Block& block) {
    if (block.state != BlockState::Writeback || block.writeback_batch != taken.token) return;
    block.writeback_batch = 0;
    set_state(block, BlockState::Clean);
  };
  FileEntry& entry = files_[taken.file];
  const std::size_t in_writeback = inactive_.blocks_in(BlockState::Writeback) + active_.blocks_in(BlockState::Writeback);
  if (entry.blocks <= in_writeback) {
    for (FileOrder* flist : {&entry.inactive, &entry.active}) {
      for (Block& block : *flist) end(block);
    }
  } else {
    for (LruList* list : {&inactive_, &active_}) {
      Block* block = list->front(BlockState::Writeback);
      while (block != nullptr) {
        Block* next = list->next(*block, BlockState::Writeback);
        end(*block);
        block = next;
      }
    }
  }
  settle();
  if (progress_hook_) progress_hook_();
}

std::int64_t PageCache::evict(std::int64_t amount, FileId excluded) {
  std::int64_t evicted = 0;
  auto take = [&](Block& block) {
    Block& victim = block.size > amount - evicted ? split_front(block, amount - evicted) : block;
    evicted += victim.size;
    evicted_total_ += victim.size;
    destroy(victim);
  };
  // One reclaim pass; `spare_written` also skips the files open for writing.
  auto pass = [&](bool spare_written) {
    auto spared = [&](const Block& block) {
      return block.file == excluded || (spare_written && files_[block.file].writers > 0);
    };
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      if (kind == ListKind::Active && settings_.reclaim_inactive_only) break;
      if (spare_written) {
        // The same victims in the same order as the walk below, without walking past the
        // clean blocks of the files being written.
        bool set_aside = false;
        while (evicted < amount) {
          Block* victim = next_unwritten_clean(kind, excluded, set_aside);
          if (victim == nullptr) break;
          take(*victim);
        }
        // Only other files' blocks were taken: the excluded file's first clean block is the same.
        if (set_aside) reclaimable(kind).lower(excluded, file_clean_list(files_[excluded], kind).front().order);
        continue;
      }
      LruList& list = list_of(kind);
      Block* block = list.front(BlockState::Clean);
      while (block != nullptr && evicted < amount) {
        Block* next = list.next(*block, BlockState::Clean);
        if (!spared(*block)) take(*block);
        block = next;
      }
    }
    if (settings_.reclaim_inactive_only) {
      // Active list aging (mm/vmscan.c, shrink_active_list): with no clean inactive data left,
      // the oldest active data is deactivated, and reclaimed if it is clean.
      while (evicted < amount && !active_.empty()) {
        Block& oldest = *active_.front();
        unlink(oldest);
        oldest.referenced = false;
        append(oldest, ListKind::Inactive);
        if (oldest.state == BlockState::Clean && !spared(oldest)) take(oldest);
      }
    }
  };
  pass(settings_.protect_files_being_written);
  if (evicted < amount && settings_.protect_files_being_written) pass(false);
  settle();
  return evicted;
}

Block* PageCache::next_unwritten_clean(ListKind kind, FileId excluded, bool& set_aside) {
  // The least recently used clean block, unless spared; if it is, the first clean block of
  // the top file of reclaimable_, once the top's key is that block's.
  Block* front = list_of(kind).front(BlockState::Clean);
  if (front == nullptr) return nullptr;
  if (front->file != excluded && files_[front->file].writers == 0) return front;
  FileHeap& files = reclaimable(kind);
  while (!files.empty()) {
    const FileHeap::Entry top = files.top();
    FileEntry& entry = files_[top.file];
    FileCleanOrder& clean = file_clean_list(entry, kind);
    if (clean.empty() || entry.writers > 0) {
      files.pop();
    } else if (clean.front().order != top.key) {
      files.raise_top(clean.front().order);
    } else if (top.file == excluded) {
      files.pop();
      set_aside = true;
    } else {
      return &clean.front();
    }
  }
  return nullptr;
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
      if (!clean.empty()) reclaimable(kind).lower(file, clean.front().order);
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
    Block* front = active_.front();
    PC_ASSERT(front != nullptr);
    Block& block = front->size > to_move ? split_front(*front, to_move) : *front;
    to_move -= block.size;
    unlink(block);
    block.referenced = false;
    append(block, ListKind::Inactive);
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
  std::size_t blocks_in_files = 0;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    const FileEntry& entry = files_[f];
    std::int64_t bytes[2] = {0, 0};
    std::int64_t dirty_bytes = 0;
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      const FileOrder& flist = kind == ListKind::Inactive ? entry.inactive : entry.active;
      // Its clean list holds its clean blocks in the list, in order; and its place in
      // reclaimable_.
      const FileCleanOrder& clean = kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
      auto clean_it = clean.begin();
      if (settings_.protect_files_being_written) {
        for (const Block& b : flist) {
          if (b.state != BlockState::Clean) continue;
          PC_ASSERT_MSG(clean_it != clean.end() && &*clean_it == &b, fmt::format("file {}: clean list out of order", f));
          ++clean_it;
        }
      }
      PC_ASSERT_MSG(clean_it == clean.end(), fmt::format("file {}: a block on its clean list in error", f));
      if (!clean.empty() && entry.writers == 0) {
        const FileHeap& files = reclaimable_[static_cast<std::size_t>(kind)];
        const auto file = static_cast<FileId>(f);
        PC_ASSERT_MSG(files.contains(file) && files.key(file) <= clean.front().order,
                      fmt::format("file {} missing from the reclaimable files, or its key too high", f));
      }
      // The file's list follows the LRU list's order.
      const LruList& lru = list(kind);
      auto lru_it = lru.blocks().begin();
      for (const Block& b : flist) {
        PC_ASSERT_MSG(b.file == f && b.list == kind, "block on the wrong file or list");
        while (lru_it != lru.blocks().end() && &*lru_it != &b) ++lru_it;
        PC_ASSERT_MSG(lru_it != lru.blocks().end(), "file list out of LRU order");
        bytes[static_cast<int>(kind)] += b.size;
        if (b.state == BlockState::Dirty) dirty_bytes += b.size;
        ++blocks_in_files;
      }
    }
    PC_ASSERT_MSG(bytes[0] == entry.inactive_bytes && bytes[1] == entry.active_bytes,
                  fmt::format("file {} byte counters disagree with its blocks", f));
    PC_ASSERT(dirty_bytes == entry.dirty_bytes);
    PC_ASSERT_MSG(entry.blocks == static_cast<std::size_t>(std::distance(entry.inactive.begin(), entry.inactive.end()) +
                                                          std::distance(entry.active.begin(), entry.active.end())),
                  fmt::format("file {}: block count disagrees with its lists", f));
  }
  PC_ASSERT_MSG(blocks_in_files == inactive_.size() + active_.size(), "a block is missing from its file's list");
  for (const FileHeap& files : reclaimable_) {
    files.check();
    PC_ASSERT(settings_.protect_files_being_written || files.empty());
  }
  std::size_t dirty_blocks = 0;
  double previous = -std::numeric_limits<double>::infinity();
  for (const Block& b : dirty_by_age_) {
    PC_ASSERT_MSG(b.state == BlockState::Dirty, "a block on the list by age is not dirty");
    PC_ASSERT_MSG(b.entry_time >= previous, "dirty blocks out of age order");
    previous = b.entry_time;
    ++dirty_blocks;
  }
  PC_ASSERT_MSG(dirty_blocks == inactive_.blocks_in(BlockState::Dirty) + active_.blocks_in(BlockState::Dirty),
                "a dirty block is missing from the list by age");
  PC_ASSERT(pool_.in_use() == inactive_.size() + active_.size());
  if (expiry_scan_.after != nullptr) {
    const Block& after = *expiry_scan_.after;
    PC_ASSERT_MSG(after.state == BlockState::Dirty && after.lru_hook.is_linked(), "the expiry search stopped at a block no longer dirty");
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
