// PageCache: files held by byte range — which parts of a file are cached, for reads of parts
// of files (access patterns).

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

void PageCache::track_ranges(FileId file) {
  if (ranged(file)) return;
  if (file >= ranged_.size()) ranged_.resize(static_cast<std::size_t>(file) + 1, 0);
  ranged_[file] = 1;
  FileEntry& entry = file_entry(file);
  std::int64_t offset = 0;
  for (FileOrder* flist : {&entry.inactive, &entry.active}) {
    for (BlockId id = flist->front(); id != kNoBlock; id = FileOrder::next(blocks_, id)) {
      blocks_[id].ranged = true;
      ranges_.insert(file, id, offset, blocks_[id].size);
      offset += blocks_[id].size;
    }
  }
  if (checking_) check_invariants();
}

std::int64_t PageCache::ranged_end(FileId file) const noexcept {
  const BlockId last = ranges_.last(file);
  return last == kNoBlock ? 0 : ranges_.end(last);
}

BlockId PageCache::block_at_or_after(FileId file, std::int64_t offset) const noexcept {
  const FileRanges::Around at = ranges_.around(file, offset);
  if (at.floor != kNoBlock && ranges_.end(at.floor) > offset) return at.floor;
  return at.above;
}

std::int64_t PageCache::cached_in(FileId file, std::int64_t offset, std::int64_t bytes) const noexcept {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  std::int64_t cached = 0;
  // Each step down the index is a few cache misses under random access: the next block is
  // looked up only when the range goes past this one.
  for (BlockId id = block_at_or_after(file, offset); id != kNoBlock;) {
    const std::int64_t start = ranges_.offset(id);
    if (start >= end) break;
    const std::int64_t stop = start + blocks_[id].size;
    cached += std::min(end, stop) - std::max(offset, start);
    if (stop >= end) break;
    id = ranges_.next(file, id);
  }
  return cached;
}

BlockId PageCache::new_ranged_block(FileId file, std::int64_t offset, std::int64_t size, BlockState state, double now) {
  const BlockId id = new_block(file, size, state, now);
  blocks_[id].ranged = true;
  ranges_.insert(file, id, offset, size);
  return id;
}

BlockId PageCache::cut_before(BlockId id, std::int64_t offset) {
  const std::int64_t head = offset - ranges_.offset(id);
  PC_ASSERT(head >= 0 && head < blocks_[id].size);
  if (head == 0) return id;
  const FileId file = blocks_[id].file;
  split_front(id, head);
  return ranges_.next(file, id);
}

void PageCache::move_ranged(BlockId id, ListKind to) {
  Block& block = blocks_[id];
  unlink(id);
  block.referenced = false;
  const BlockId tail_id = list_of(to).back();
  if (block.state == BlockState::Clean && tail_id != kNoBlock) {
    const Block& tail = blocks_[tail_id];
    if (tail.file == block.file && tail.ranged && tail.state == BlockState::Clean && !tail.referenced &&
        ranges_.offset(tail_id) + tail.size == ranges_.offset(id)) {
      // Contiguous clean data of the file, one after the other at the MRU end: one block.
      const std::int64_t size = block.size;
      block.size = 0;
      ranges_.erase(block.file, id);
      blocks_.give_back(id);
      list_of(to).resize(tail_id, tail.size + size);
      ranges_.resize(tail_id, tail.size);
      FileEntry& entry = files_[tail.file];
      (to == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += size;
      charge(tail.file, size);
      return;
    }
  }
  append(id, to);
}

void PageCache::add_ranged(FileId file, std::int64_t offset, std::int64_t bytes, BlockState state, double now, bool referenced) {
  LruList& list = list_of(ListKind::Inactive);
  const BlockId tail_id = list.back();
  if (tail_id != kNoBlock) {
    const Block& tail = blocks_[tail_id];
    if (tail.file == file && tail.ranged && tail.state == state && tail.referenced == referenced &&
        (state == BlockState::Clean || tail.entry_time == now) && ranges_.offset(tail_id) + tail.size == offset) {
      list.resize(tail_id, tail.size + bytes);
      ranges_.resize(tail_id, tail.size);
      FileEntry& entry = files_[file];
      entry.inactive_bytes += bytes;
      charge(file, bytes);
      if (state == BlockState::Dirty) {
        entry.dirty_bytes += bytes;
        charge_dirty(file, bytes);
      }
      return;
    }
  }
  const BlockId id = new_ranged_block(file, offset, bytes, state, now);
  blocks_[id].referenced = referenced;
  append(id, ListKind::Inactive);
  if (state == BlockState::Dirty) dirty_by_age_.push_back(blocks_, id);  // time only goes forward: the newest
}

std::int64_t PageCache::read_range(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  // The cached parts, by offset, each block cut to the part read; then the holes between them.
  std::int64_t at = offset;
  std::int64_t held_to = offset;  // [offset, held_to) cached without a hole
  const BlockId first = block_at_or_after(file, offset);
  const bool none_cached = first == kNoBlock || ranges_.offset(first) >= end;
  for (BlockId id = first; !none_cached && id != kNoBlock && ranges_.offset(id) < end;) {
    id = cut_before(id, std::max(at, ranges_.offset(id)));
    if (ranges_.offset(id) + blocks_[id].size > end) split_front(id, end - ranges_.offset(id));
    if (ranges_.offset(id) == held_to) held_to += blocks_[id].size;
    at = ranges_.offset(id) + blocks_[id].size;
    const BlockId next = at < end ? ranges_.next(file, id) : kNoBlock;
    Block& block = blocks_[id];
    if (block.list == ListKind::Active) {
      move_ranged(id, ListKind::Active);
    } else {
      switch (policy_->reread(block)) {
        case Policy::Reread::Mark: block.referenced = true; break;
        case Policy::Reread::Activate: move_ranged(id, ListKind::Active); break;
        case Policy::Reread::Refresh: move_ranged(id, ListKind::Inactive); break;
      }
    }
    id = next;
  }
  // The holes after the cached prefix; with nothing cached, from the first look-up's answer.
  const std::int64_t missing = fill_holes(file, held_to, end, now, first_touch_, none_cached ? &first : nullptr);
  if (missing > 0) policy_->missed(*this, file, missing);
  balance();  // after every read, under every policy
  settle();
  return missing;
}

std::int64_t PageCache::fill_holes(FileId file, std::int64_t offset, std::int64_t end, double now, bool referenced, const BlockId* first) {
  std::int64_t added = 0;
  for (std::int64_t at = offset; at < end; first = nullptr) {
    const BlockId id = first != nullptr ? *first : block_at_or_after(file, at);
    const std::int64_t hole_end = id == kNoBlock ? end : std::min(end, ranges_.offset(id));
    if (hole_end > at) {
      if (hole_end - at > free()) throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", hole_end - at, free()));
      add_ranged(file, at, hole_end - at, BlockState::Clean, now, referenced);
      added += hole_end - at;
    }
    at = id == kNoBlock ? end : ranges_.offset(id) + blocks_[id].size;
  }
  return added;
}

std::int64_t PageCache::read_ahead(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t added = fill_holes(file, offset, offset + bytes, now, false);
  if (added > 0) settle();
  return added;
}

std::int64_t PageCache::drop_clean_range(FileId file, std::int64_t offset, std::int64_t bytes) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  std::int64_t dropped = 0;
  for (BlockId id = block_at_or_after(file, offset); id != kNoBlock && ranges_.offset(id) < end;) {
    id = cut_before(id, std::max(offset, ranges_.offset(id)));
    if (ranges_.end(id) > end) split_front(id, end - ranges_.offset(id));
    const BlockId next = ranges_.end(id) < end ? ranges_.next(file, id) : kNoBlock;
    if (blocks_[id].state == BlockState::Clean) {
      dropped += blocks_[id].size;
      destroy(id);
    }
    id = next;
  }
  settle();
  if (dropped > 0 && progress_hook_) progress_hook_();
  return dropped;
}

std::int64_t PageCache::write_range(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  std::int64_t missing = 0;
  for (std::int64_t at = offset; at < end;) {
    BlockId id = block_at_or_after(file, at);
    const std::int64_t hole_end = id == kNoBlock ? end : std::min(end, ranges_.offset(id));
    if (hole_end > at) {
      if (hole_end - at > free()) throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", hole_end - at, free()));
      add_ranged(file, at, hole_end - at, BlockState::Dirty, now, false);
      missing += hole_end - at;
      at = hole_end;
      continue;
    }
    // A cached part: cut to what the write covers.
    id = cut_before(id, at);
    if (ranges_.offset(id) + blocks_[id].size > end) split_front(id, end - ranges_.offset(id));
    const std::int64_t size = blocks_[id].size;
    if (blocks_[id].state != BlockState::Dirty) {
      // Its pages are written anew: the same memory, now dirty data entered now.
      destroy(id);
      add_ranged(file, at, size, BlockState::Dirty, now, false);
    }
    at += size;
  }
  peak_dirty_ = std::max(peak_dirty_, dirty());
  settle();
  return missing;
}

void PageCache::commit_dirty_at(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(bytes >= 0 && bytes <= reserved_);
  reserved_ -= bytes;
  write_range(file, offset, bytes, now);
  if (progress_hook_) progress_hook_();
}

void PageCache::check_ranges(std::size_t f, std::size_t most) const {
  const auto file = static_cast<FileId>(f);
  const FileEntry& entry = files_[f];
  if (!ranged(file)) {
    PC_ASSERT_MSG(ranges_.empty(file), fmt::format("file {}: offsets indexed for a file not held by range", f));
    for (const FileOrder* flist : {&entry.inactive, &entry.active}) {
      for (const Block& block : flist->range(blocks_)) PC_ASSERT_MSG(!block.ranged, fmt::format("file {}: a ranged block", f));
    }
    return;
  }
  const std::size_t indexed = ranges_.check(file, most);
  PC_ASSERT_MSG(indexed == entry.blocks, fmt::format("file {}: {} blocks indexed by offset, {} in its lists", f, indexed, entry.blocks));
  std::int64_t end = 0;
  ranges_.for_each(file, [&](BlockId id) {
    const Block& block = blocks_[id];
    PC_ASSERT_MSG(block.ranged && block.file == file && block.size > 0, fmt::format("file {}: block {} indexed wrongly", f, id));
    PC_ASSERT_MSG(ranges_.offset(id) >= end, fmt::format("file {}: block {} overlaps the one before", f, id));
    PC_ASSERT_MSG(ranges_.end(id) == ranges_.offset(id) + block.size, fmt::format("file {}: block {}'s end is not indexed", f, id));
    end = ranges_.offset(id) + block.size;
  });
}

}  // namespace pagecache::cache
