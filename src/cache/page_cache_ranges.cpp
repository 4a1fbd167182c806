// PageCache: files held by byte range — which parts of a file are cached, for reads of parts
// of files (access patterns).

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

void PageCache::track_ranges(FileId file) {
  if (ranged(file)) return;
  ranges_.track(file);
  FileEntry& entry = file_entry(file);
  std::int64_t offset = 0;
  for (FileOrder* flist : {&entry.inactive, &entry.active}) {
    for (BlockId id = flist->front(); id != kNoBlock; id = FileOrder::next(blocks_, id)) {
      blocks_[id].ranged = true;
      ranges_.insert(file, id, offset, blocks_[id].size);
      offset += blocks_[id].size;
    }
  }
  if (checking_) check_after_operation();
}

BlockId PageCache::new_ranged_block(FileId file, std::int64_t offset, std::int64_t size, BlockState state, double now, NodeId node) {
  const BlockId id = new_block(file, size, state, now, node);
  blocks_[id].ranged = true;
  ranges_.insert(file, id, offset, size);
  return id;
}

PageCache::Located PageCache::cut(Located block, std::int64_t offset, std::int64_t end) {
  PC_ASSERT(offset >= block.offset && offset < block.end && end > offset);
  if (offset > block.offset) {
    // The part from `offset` is the new block right after the head, in its list too.
    split_front(block.id, offset - block.offset);
    block = {list_of(blocks_[block.id].list).next(block.id), offset, block.end};
  }
  if (block.end > end) {
    split_front(block.id, end - block.offset);
    block.end = end;
  }
  return block;
}

void PageCache::move_ranged(BlockId id, std::int64_t offset, ListKind to) {
  Block& block = blocks_[id];
  unlink(id);
  block.referenced = false;
  const BlockId tail_id = list_of(to).back();
  if (block.state == BlockState::Clean && tail_id != kNoBlock) {
    const Block& tail = blocks_[tail_id];
    if (tail.file == block.file && tail.ranged && tail.state == BlockState::Clean && !tail.referenced && tail.policy_bits == block.policy_bits &&
        tail.node == block.node &&
        ranges_.end(tail_id) == offset) {
      // Contiguous clean data of the file, one after the other at the MRU end: one block.
      const std::int64_t size = block.size;
      block.size = 0;
      ranges_.erase(block.file, id);
      blocks_.give_back(id);
      list_of(to).resize(tail_id, tail.size + size);
      ranges_.resize(tail.file, tail_id, tail.size);
      FileEntry& entry = files_[tail.file];
      (to == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += size;
      charge(tail.file, tail.node, size);
      return;
    }
  }
  append(id, to);
}

void PageCache::place_ranged(FileId file, std::int64_t offset, std::int64_t bytes, BlockState state, double now, Placement at) {
  if (nodes_.empty()) return add_ranged(file, offset, bytes, state, now, at, 0);
  nodes_.place(bytes, nodes_.toucher(), [&](NodeId node, std::int64_t part) {
    if (node != nodes_.toucher()) nodes_.remote().cache += part;
    add_ranged(file, offset, part, state, now, at, node);
    offset += part;
  });
}

void PageCache::add_ranged(FileId file, std::int64_t offset, std::int64_t bytes, BlockState state, double now, Placement at, NodeId node) {
  PC_ASSERT(state == BlockState::Clean || at.list == ListKind::Inactive);
  LruList& list = list_of(at.list);
  const BlockId tail_id = list.back();
  if (tail_id != kNoBlock) {
    const Block& tail = blocks_[tail_id];
    if (tail.file == file && tail.ranged && tail.state == state && tail.referenced == at.referenced && tail.policy_bits == at.bits &&
        tail.node == node &&
        (state == BlockState::Clean || tail.entry_time == now) && ranges_.offset(tail_id) + tail.size == offset) {
      list.resize(tail_id, tail.size + bytes);
      ranges_.resize(file, tail_id, tail.size);
      FileEntry& entry = files_[file];
      (at.list == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += bytes;
      charge(file, node, bytes);
      if (state == BlockState::Dirty) {
        entry.dirty_bytes += bytes;
        groups_.charge_dirty(file, bytes);
      }
      return;
    }
  }
  const BlockId id = new_ranged_block(file, offset, bytes, state, now, node);
  blocks_[id].referenced = at.referenced;
  set_policy_bits(blocks_[id], at.bits);
  append(id, at.list);
  if (state == BlockState::Dirty) dirty_by_age_.push_back(blocks_, id);  // time only goes forward: the newest
}

std::int64_t PageCache::read_range(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  // The cached parts, by offset, each block cut to the part read; then the holes between them.
  // Spans come from the look-ups (the side array would be a cache miss per block).
  std::int64_t held_to = offset;  // [offset, held_to) cached without a hole
  const Located first = ranges_.at_or_after(file, offset);
  const bool none_cached = first.id == kNoBlock || first.offset >= end;
  for (Located at = first; !none_cached && at.id != kNoBlock && at.offset < end;) {
    const Located part = cut(at, std::max(offset, at.offset), end);
    if (part.offset == held_to) held_to = part.end;
    at = part.end < end ? ranges_.at_or_after(file, part.end) : Located{};
    Block& block = blocks_[part.id];
    if (block.node != nodes_.toucher()) nodes_.remote().reread += block.size;
    if (in_place_) {
      set_policy_bits(block, policy_->reread_bits(block));
    } else if (block.list == ListKind::Active) {
      move_ranged(part.id, part.offset, ListKind::Active);
    } else {
      switch (policy_->reread(block)) {
        case Policy::Reread::Mark: block.referenced = true; break;
        case Policy::Reread::Activate: move_ranged(part.id, part.offset, ListKind::Active); break;
        case Policy::Reread::Refresh: move_ranged(part.id, part.offset, ListKind::Inactive); break;
      }
    }
  }
  // The holes after the cached prefix; with nothing cached, from the first look-up's answer.
  const std::int64_t missing = fill_holes(file, held_to, end, now, true, none_cached ? &first : nullptr);
  if (missing > 0) policy_->missed(*this, file, missing);
  if (balance_reads_) balance();  // after every read, under every policy that balances
  settle();
  return missing;
}

std::int64_t PageCache::fill_holes(FileId file, std::int64_t offset, std::int64_t end, double now, bool demand, const Located* first) {
  std::int64_t added = 0;
  for (std::int64_t at = offset; at < end; first = nullptr) {
    const Located next = first != nullptr ? *first : ranges_.at_or_after(file, at);
    const std::int64_t hole_end = next.id == kNoBlock ? end : std::min(end, next.offset);
    if (hole_end > at) {
      if (hole_end - at > free()) throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", hole_end - at, free()));
      add_arriving(file, at, hole_end - at, now, demand);
      added += hole_end - at;
    }
    at = next.id == kNoBlock ? end : next.end;
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
  for (Located at = ranges_.at_or_after(file, offset); at.id != kNoBlock && at.offset < end;) {
    const Located part = cut(at, std::max(offset, at.offset), end);
    at = part.end < end ? ranges_.at_or_after(file, part.end) : Located{};
    if (blocks_[part.id].state == BlockState::Clean) {
      dropped += part.end - part.offset;
      destroy(part.id);
    }
  }
  settle();
  if (dropped > 0 && listeners_.progress) listeners_.progress();
  return dropped;
}

std::int64_t PageCache::write_range(FileId file, std::int64_t offset, std::int64_t bytes, double now) {
  PC_ASSERT(ranged(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  std::int64_t missing = 0;
  for (std::int64_t at = offset; at < end;) {
    const Located next = ranges_.at_or_after(file, at);
    const std::int64_t hole_end = next.id == kNoBlock ? end : std::min(end, next.offset);
    if (hole_end > at) {
      if (hole_end - at > free()) throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", hole_end - at, free()));
      place_ranged(file, at, hole_end - at, BlockState::Dirty, now, {});
      missing += hole_end - at;
      at = hole_end;
      continue;
    }
    // A cached part: cut to what the write covers.
    const Located part = cut(next, at, end);
    if (blocks_[part.id].state != BlockState::Dirty) {
      // Its pages are written anew: the same memory, now dirty data entered now.
      const NodeId node = blocks_[part.id].node;
      destroy(part.id);
      add_ranged(file, at, part.end - part.offset, BlockState::Dirty, now, {}, node);
    }
    at = part.end;
  }
  totals_.peak_dirty = std::max(totals_.peak_dirty, dirty());
  settle();
  return missing;
}

void PageCache::check_ranges(std::size_t f, std::size_t most) const {
  const auto file = static_cast<FileId>(f);
  const FileEntry& entry = files_[f];
  if (!ranged(file)) {
    for (const FileOrder* flist : {&entry.inactive, &entry.active}) {
      for (const Block& block : flist->range(blocks_)) PC_ASSERT_MSG(!block.ranged, fmt::format("file {}: a ranged block", f));
    }
    return;
  }
  const std::size_t indexed = ranges_.check(file, most);
  PC_ASSERT_MSG(indexed == entry.blocks, fmt::format("file {}: {} blocks indexed by offset, {} in its lists", f, indexed, entry.blocks));
  ranges_.for_each(file, [&](BlockId id) {
    const Block& block = blocks_[id];
    PC_ASSERT_MSG(block.ranged && block.file == file && block.size > 0, fmt::format("file {}: block {} indexed wrongly", f, id));
    PC_ASSERT_MSG(ranges_.end(id) == ranges_.offset(id) + block.size, fmt::format("file {}: block {}'s end is not its size", f, id));
  });
}

}  // namespace pagecache::cache
