// PageCache: reclaim (eviction of clean data) and the balance of the active and inactive lists.

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace pagecache::cache {

namespace {

// Reclaim's next victims, ahead of their turn: a random reader evicts a page a request, each a
// few cache misses. The front's leaf in the offset index (its span came with the call before),
// and the span and block after it.
void prefetch_victims(const LruList& list, const BlockPool& blocks, const FileRanges& ranges) noexcept {
  const BlockId front = list.front(BlockState::Clean);
  if (front == kNoBlock || !blocks[front].ranged) return;
  ranges.prefetch_leaf(blocks[front].file, front);
  const BlockId after = list.next_in_state(front);
  if (after == kNoBlock) return;
  __builtin_prefetch(&blocks[after]);
  ranges.prefetch_span(after);
}

}  // namespace

std::int64_t PageCache::evict(std::int64_t amount, FileId excluded, GroupId group) {
  PC_ASSERT_MSG(group != kRootGroup, "a reclaim targets one group other than the root, or all");
  target_ = group;
  std::int64_t evicted = 0;
  if (amount > 0) evicted = nodes_.empty() || group != kAnyGroup ? policy_->reclaim(*this, amount, excluded) : evict_by_node(amount, excluded);
  target_ = kAnyGroup;
  if (evicted > 0) prefetch_victims(inactive_, blocks_, ranges_);
  settle();
  listeners_.tracer.eviction(evicted);
  return evicted;
}

std::int64_t PageCache::evict_clean(ListKind kind, std::int64_t budget, FileId excluded, bool spare_written) {
  PC_ASSERT(!spare_written || index_clean_);
  std::int64_t evicted = 0;
  auto take = [&](BlockId id) { evicted += evict_front(id, budget - evicted, kind); };
  if (spare_written && target_node_ == kAnyNode) {
    // The same victims in the same order as the walks below, without walking past the clean
    // blocks of the files being written (or of other groups).
    bool set_aside = false;
    while (evicted < budget) {
      const BlockId victim = next_unwritten_clean(kind, excluded, set_aside);
      if (victim == kNoBlock) break;
      take(victim);
    }
    // Only other files' blocks were taken: the excluded file's first clean block is the same.
    if (set_aside) {
      const bool by_group = target_ != kAnyGroup;
      reclaimable(kind, by_group).lower(by_group ? target_ : 0, excluded, blocks_[file_clean_list(files_[excluded], kind).front()].order);
    }
    return evicted;
  }
  const LruList& list = list_of(kind);
  auto eligible = [&](const Block& block) {
    return block.file != excluded && in_target(block) && !(spare_written && files_[block.file].writers > 0);
  };
  if (nodes_.empty() || target_node_ != kAnyNode) {
    // One node's clean blocks: its own sub-list (a one-node host's are all node 0's).
    BlockId id = list.front(BlockState::Clean, target_node_ == kAnyNode ? 0 : target_node_);
    while (id != kNoBlock && evicted < budget) {
      const BlockId next = list.next_in_state(id);
      if (eligible(blocks_[id])) take(id);
      id = next;
    }
    return evicted;
  }
  // Every node's clean blocks in the list's order: the older of the nodes' next ones each time.
  std::array<BlockId, kMaxNodes> at;
  at.fill(kNoBlock);
  for (NodeId n = 0; n < nodes_.size(); ++n) at[n] = list.front(BlockState::Clean, n);
  while (evicted < budget) {
    std::size_t oldest = kMaxNodes;
    for (std::size_t n = 0; n < kMaxNodes; ++n) {
      if (at[n] != kNoBlock && (oldest == kMaxNodes || blocks_[at[n]].order < blocks_[at[oldest]].order)) oldest = n;
    }
    if (oldest == kMaxNodes) break;
    const BlockId id = at[oldest];
    at[oldest] = list.next_in_state(id);
    if (eligible(blocks_[id])) take(id);
  }
  return evicted;
}

std::int64_t PageCache::evict_front(BlockId id, std::int64_t bytes, ListKind from) {
  const BlockId victim = front_part(id, bytes);
  const Block& block = blocks_[victim];
  const Policy::Evicted gone{.file = block.file,
                             .from = from,
                             .bytes = block.size,
                             .offset = block.ranged && arrivals_ ? ranges_.offset(victim) : kNoOffset,
                             .bits = block.policy_bits};
  totals_.evicted += gone.bytes;
  destroy(victim);
  policy_->evicted(*this, gone);
  return gone.bytes;
}

void PageCache::move_to_back(BlockId id, ListKind to, bool referenced) {
  unlink(id);
  blocks_[id].referenced = referenced;
  append(id, to);
}

BlockId PageCache::front_part(BlockId id, std::int64_t bytes) {
  if (blocks_[id].ranged) {
    // Up to a page boundary of the file: a page is freed or aged whole, and cutting one in two
    // at every eviction (a memory that is not a number of pages) would make a block of each.
    const std::int64_t start = ranges_.offset(id);
    const std::int64_t page = ranges_.page_size();
    bytes = (start + bytes + page - 1) / page * page - start;
  }
  return blocks_[id].size > bytes ? split_front(id, bytes) : id;
}

std::int64_t PageCache::deactivate_oldest(std::int64_t budget, FileId excluded, bool spare_written) {
  std::int64_t evicted = 0;
  // The oldest active data of the target: the list's front, or with a group target the first
  // of the group's blocks from the front (others' blocks stay where they are).
  BlockId at = active_.front();
  while (evicted < budget && at != kNoBlock) {
    const BlockId oldest = at;
    at = active_.next(oldest);
    Block& block = blocks_[oldest];
    if (!in_target(block)) continue;
    move_to_back(oldest, ListKind::Inactive, false);
    const bool spared = block.file == excluded || (spare_written && files_[block.file].writers > 0);
    if (block.state != BlockState::Clean || spared) continue;
    evicted += evict_front(oldest, budget - evicted, ListKind::Active);  // chosen as the oldest active data
  }
  return evicted;
}

// reclaimable_, per LRU list: every file not being written that has clean data in the list is
// in it, under a key no higher than the order key of its first clean block there. Keys are
// lowered at once (a clean block comes first in the file's clean list, or the file's last write
// ends) and raised, or the file dropped (it has no clean data left there, or is being written),
// only when the file comes to the top: so when the top's key is its first clean block's, that
// block is the least recently used clean block of any file not being written. Two files' first
// clean blocks never share an order key (equal keys are pieces of one file's block).
BlockId PageCache::next_unwritten_clean(ListKind kind, FileId excluded, bool& set_aside) {
  // The least recently used clean block (of any node), unless spared; if it is, the first
  // clean block of the top file of reclaimable_, once the top's key is that block's.
  const LruList& list = list_of(kind);
  BlockId front = list.front(BlockState::Clean);
  for (NodeId n = 1; n < nodes_.size(); ++n) {
    const BlockId other = list.front(BlockState::Clean, n);
    if (other != kNoBlock && (front == kNoBlock || blocks_[other].order < blocks_[front].order)) front = other;
  }
  if (front == kNoBlock) return kNoBlock;
  const FileId front_file = blocks_[front].file;
  if (front_file != excluded && files_[front_file].writers == 0 && in_target(blocks_[front])) return front;
  // A group's reclaim: its own heap (a file stays in its group).
  const bool by_group = target_ != kAnyGroup;
  const std::size_t heap = by_group ? target_ : 0;
  FileHeaps& files = reclaimable(kind, by_group);
  if (heap >= files.heaps()) return kNoBlock;
  while (!files.empty(heap)) {
    const FileHeaps::Entry top = files.top(heap);
    FileEntry& entry = files_[top.file];
    FileCleanOrder& clean = file_clean_list(entry, kind);
    if (clean.empty() || entry.writers > 0) {
      files.pop(heap);
    } else if (blocks_[clean.front()].order != top.key) {
      files.raise_top(heap, blocks_[clean.front()].order);
    } else if (top.file == excluded) {
      files.pop(heap);
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
  if (!index_clean_ || was_written == (entry.writers > 0)) return;
  // Its last write ended: the file is among those eviction may take from while sparing the
  // files being written. (Its first write started: it leaves them when it comes to the top.)
  if (!writing) {
    for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
      const FileCleanOrder& clean = file_clean_list(entry, kind);
      if (!clean.empty()) mark_reclaimable(kind, file, blocks_[clean.front()].order);
    }
  }
  if (checking_) check_after_operation();
}

void PageCache::balance() {
  const std::int64_t excess = active_.bytes() - 2 * inactive_.bytes();
  if (excess <= 0) return;
  // Moving x bytes leaves active - x <= 2 (inactive + x): x >= excess / 3, rounded up.
  std::int64_t to_move = (excess + 2) / 3;
  while (to_move > 0) {
    const BlockId front = active_.front();
    PC_ASSERT(front != kNoBlock);
    const BlockId id = front_part(front, to_move);
    to_move -= blocks_[id].size;
    unlink(id);
    blocks_[id].referenced = false;
    append(id, ListKind::Inactive);
  }
}

}  // namespace pagecache::cache
