// PageCache: reads of cached data of files held whole (not by range), as the policy says:
// moved to a list's most recently used end or marked (reaccess), or left in place with the
// policy's bits updated (reaccess_in_place).

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <algorithm>

namespace pagecache::cache {

BlockId PageCache::resume_point(const FileEntry& entry, FileId file, ReadCursor from) const noexcept {
  if (from.block != kNoBlock) {
    const Block& b = blocks_[from.block];
    if (b.size > 0 && b.file == file && b.list == ListKind::Inactive && b.order == from.order) {
      return from.after ? FileOrder::next(blocks_, from.block) : from.block;
    }
  }
  return entry.inactive.front();
}

ReadCursor PageCache::reaccess(FileId file, std::int64_t bytes, double now, ReadCursor from) {
  PC_ASSERT(bytes >= 0 && bytes <= cached(file));
  PC_ASSERT_MSG(!ranged(file), "a file held by range is re-accessed by range (read_range)");
  if (in_place_) return reaccess_in_place(file, bytes, from);
  FileEntry& entry = file_entry(file);
  std::int64_t left = bytes;
  std::int64_t merged_clean[2][kMaxNodes] = {};  // by the list it goes to and the node it is on
  // A block read moves to the MRU end of `to`: clean data read is merged into one new block
  // there; dirty (or writeback) data moves on its own, keeping its entry time.
  auto move = [&](BlockId id, ListKind to) {
    Block& block = blocks_[id];
    if (block.state == BlockState::Clean) {
      merged_clean[static_cast<int>(to)][block.node] += block.size;
      destroy(id);
    } else {
      unlink(id);
      block.referenced = false;
      append(id, to);
    }
  };
  // Inactive blocks, least recently used first, from `start`; each as the policy says.
  // Returns where a next chunk of the same read starts.
  auto touch_inactive = [&](BlockId start) {
    const BlockId last = entry.inactive.back();
    BlockId at = start;
    while (left > 0 && at != kNoBlock) {
      const BlockId id = blocks_[at].size > left ? split_front(at, left) : at;
      at = FileOrder::next(blocks_, id);
      Block& block = blocks_[id];
      left -= block.size;
      if (block.node != nodes_.toucher()) nodes_.remote().reread += block.size;
      const Policy::Reread what = policy_->reread(block);
      switch (what) {
        case Policy::Reread::Mark: block.referenced = true; break;
        case Policy::Reread::Activate: move(id, ListKind::Active); break;
        case Policy::Reread::Refresh: move(id, ListKind::Inactive); break;
      }
      if (id == last) {
        // The blocks refreshed are behind it; data added later comes after it, if it stayed.
        return what == Policy::Reread::Mark ? ReadCursor{.block = id, .after = true, .order = block.order} : ReadCursor{};
      }
    }
    return at != kNoBlock ? ReadCursor{.block = at, .after = false, .order = blocks_[at].order} : ReadCursor{};
  };
  // Where this read left off, if that block is still there, unmoved.
  const BlockId start = resume_point(entry, file, from);
  ReadCursor cursor = touch_inactive(start);
  // Active blocks: taken from the front of the file's active list and moved to the back, so
  // that none is met twice.
  while (left > 0 && !entry.active.empty()) {
    const BlockId front = entry.active.front();
    const BlockId id = blocks_[front].size > left ? split_front(front, left) : front;
    left -= blocks_[id].size;
    if (blocks_[id].node != nodes_.toucher()) nodes_.remote().reread += blocks_[id].size;
    move(id, ListKind::Active);
  }
  // More than this read left untouched (others read or evicted meanwhile): the blocks it
  // touched before, again.
  if (left > 0) {
    touch_inactive(entry.inactive.front());
    cursor = {};
  }
  PC_ASSERT(left == 0);
  for (ListKind to : {ListKind::Active, ListKind::Inactive}) {
    for (NodeId node = 0; node < kMaxNodes; ++node) {
      const std::int64_t merged = merged_clean[static_cast<int>(to)][node];
      if (merged > 0 && !extend_tail(file, merged, Placement{.list = to}, node)) append(new_block(file, merged, BlockState::Clean, now, node), to);
    }
  }
  if (balance_reads_) balance();  // after every read, under every policy that balances
  settle();
  return cursor;
}

ReadCursor PageCache::reaccess_in_place(FileId file, std::int64_t bytes, ReadCursor from) {
  FileEntry& entry = file_entry(file);
  std::int64_t left = bytes;
  // The file's blocks of one list in LRU order from `start`, up to its block `last`; returns
  // the last block touched.
  auto touch = [&](BlockId start, BlockId last) {
    BlockId touched = kNoBlock;
    for (BlockId at = start; left > 0 && at != kNoBlock;) {
      const BlockId id = blocks_[at].size > left ? split_front(at, left) : at;
      Block& block = blocks_[id];
      left -= block.size;
      if (block.node != nodes_.toucher()) nodes_.remote().reread += block.size;
      set_policy_bits(block, policy_->reread_bits(block));
      touched = id;
      if (id == last) break;
      at = FileOrder::next(blocks_, id);
    }
    return touched;
  };
  // Inactive data from where this read left off (if that block is still there, unmoved),
  // then active data; then, if the read wants more (others read or evicted meanwhile), the
  // inactive data again from the front, as reaccess does.
  const BlockId start = resume_point(entry, file, from);
  const BlockId last = touch(start, entry.inactive.back());
  ReadCursor cursor = last != kNoBlock ? ReadCursor{.block = last, .after = true, .order = blocks_[last].order} : ReadCursor{};
  touch(entry.active.front(), entry.active.back());
  if (left > 0) {
    touch(entry.inactive.front(), entry.inactive.back());
    cursor = {};
  }
  PC_ASSERT(left == 0);
  settle();
  return cursor;
}

void PageCache::rotate(std::vector<BlockId>& blocks) {
  // In their order (pieces of one block share its key and come in the order of the list of
  // blocks in writeback), the last put at the front first.
  std::stable_sort(blocks.begin(), blocks.end(), [&](BlockId a, BlockId b) {
    const Block& x = blocks_[a];
    const Block& y = blocks_[b];
    return x.list != y.list ? x.list < y.list : x.order < y.order;
  });
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) {
    unlink(*it);
    append(*it, ListKind::Inactive, true);
  }
  blocks.clear();
}

}  // namespace pagecache::cache
