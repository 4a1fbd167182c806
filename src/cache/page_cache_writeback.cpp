// PageCache: dirty data taken for writing back (by amount, by file, by age) and returned clean.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <algorithm>
#include <limits>

namespace pagecache::cache {

std::int64_t PageCache::flush(std::int64_t amount, FileId excluded, std::vector<Flushed>& out, GroupId group) {
  PC_ASSERT_MSG(group != kRootGroup, "a flush targets one group other than the root, or all");
  target_ = group;
  std::int64_t flushed = 0;
  const std::size_t first_part = out.size();
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    LruList& list = list_of(kind);
    BlockId id = list.front(BlockState::Dirty);
    while (id != kNoBlock && flushed < amount) {
      const BlockId next = list.next_in_state(id);
      if (blocks_[id].file != excluded && in_target(blocks_[id])) {
        const bool partial = blocks_[id].size > amount - flushed;
        const BlockId target = partial ? split_front(id, amount - flushed) : id;
        const Block& block = blocks_[target];
        flushed += block.size;
        // A part per run of one file's blocks, each its own write: the caller may write the
        // parts one after the other, and a part's data is clean when its own write ends.
        if (out.size() > first_part && out.back().file == block.file) out.back().bytes += block.size;
        else out.push_back({block.file, block.size, next_token_++});
        start_writeback(target, out.back().token);
        if (partial && !policy_->splits_flushed_block_in_place()) {
          unlink(target);
          append(target, ListKind::Inactive);
        }
      }
      id = next;
    }
  }
  target_ = kAnyGroup;
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
  policy_->dropped(*this, file);
  settle();
  if (listeners_.progress) listeners_.progress();
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
  const BlockId id = policy_->next_expired(*this, cutoff);
  return id == kNoBlock ? Flushed{kNoFile, 0} : take_for_writeback(id);
}

// Where the last search for expired data stopped (expiry_scan_): every dirty block before `after`
// in next_dirty's order has an entry time later than `cutoff`. The flusher takes expired blocks
// one at a time under one cutoff; with many writers they sit behind many dirty blocks not yet
// expired, which the next search with that cutoff need not walk again. Cleared when a dirty
// block of entry time <= cutoff is linked anywhere, or when `after` leaves the dirty blocks.
BlockId PageCache::lru_expired(double cutoff) {
  // A search under the cutoff of the previous one resumes where that one stopped.
  BlockId id = kNoBlock;
  if (expiry_scan_.after != kNoBlock && expiry_scan_.cutoff == cutoff) {
    id = next_dirty(expiry_scan_.after);
  } else {
    expiry_scan_ = {};
    id = inactive_.front(BlockState::Dirty);
    if (id == kNoBlock) id = active_.front(BlockState::Dirty);
  }
  for (; id != kNoBlock; id = next_dirty(id)) {
    if (blocks_[id].entry_time <= cutoff) return id;
    expiry_scan_ = {id, cutoff};
  }
  return kNoBlock;
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
  // Whatever order they are ended in, each takes its one place in the clean sub-lists
  // (link_in_order), so the lists end up as a walk in LRU order leaves them.
  FileWriteback& in_writeback = writeback_[taken.file];
  for (BlockId id = in_writeback.front(); id != kNoBlock;) {
    const BlockId next = FileWriteback::next(blocks_, id);
    if (blocks_[id].writeback_batch == taken.token) {
      set_state(id, BlockState::Clean);
      if (rotates_) {
        if (const std::optional<std::uint8_t> bits = policy_->written_back(blocks_[id])) {
          set_policy_bits(blocks_[id], *bits);
          rotating_.push_back(id);
        }
      }
    }
    id = next;
  }
  if (!rotating_.empty()) rotate(rotating_);
  settle();
  if (listeners_.progress) listeners_.progress();
}

}  // namespace pagecache::cache
