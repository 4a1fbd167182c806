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

PageCache::PageCache(std::int64_t total_memory, const CacheSettings& settings, MemoryLayout layout, std::unique_ptr<Policy> policy)
    : settings_(settings),
      policy_(policy ? std::move(policy) : make_policy(settings)),
      index_clean_(policy_->spares_files_being_written()),
      first_touch_(policy_->read_is_first_touch()),
      balance_always_(policy_->balance() == Policy::Balance::AfterEveryChange),
      balance_reads_(policy_->balance() != Policy::Balance::Never),
      in_place_(policy_->rereads_in_place()),
      arrivals_(policy_->places_arrivals()),
      rotates_(policy_->rotates_written_back()),
      total_(total_memory),
      ranges_(layout.page_size) {
  if (total_memory <= 0) throw ConfigError(fmt::format("memory size must be > 0, got {} bytes", total_memory));
  if (layout.page_size <= 0) throw ConfigError(fmt::format("a page must be > 0 bytes, got {}", layout.page_size));
  if (layout.nodes < 1 || layout.nodes > kMaxNodes) throw ConfigError(fmt::format("a host has 1 to {} NUMA nodes, got {}", kMaxNodes, layout.nodes));
  if (layout.nodes > 1) nodes_.split(total_, layout.nodes);
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

void PageCache::allocate_anonymous(std::int64_t bytes, GroupId group) {
  PC_ASSERT(bytes >= 0);
  if (bytes > free()) {
    throw SimulationError(fmt::format("out of memory: {} bytes of application memory requested, {} free", bytes, free()));
  }
  if (!groups_.empty()) {
    if (group != kRootGroup && bytes > group_room(*this, group)) {
      throw SimulationError(fmt::format("memory group {} over its limit: {} bytes of application memory requested, {} of {} used", group,
                                        bytes, groups_.usage(group), groups_.max(group)));
    }
    groups_.charge_anonymous(group, bytes);
  } else {
    PC_ASSERT(group == kRootGroup);
  }
  anonymous_ += bytes;
  if (!nodes_.empty()) {
    nodes_.place(bytes, nodes_.toucher(), [&](NodeId node, std::int64_t part) {
      nodes_[node].anonymous += part;
      if (node != nodes_.toucher()) nodes_.remote().anonymous += part;
    });
  }
  settle();
}

void PageCache::release_anonymous(std::int64_t bytes, GroupId group) {
  PC_ASSERT(bytes >= 0 && bytes <= anonymous_);
  if (!groups_.empty()) {
    PC_ASSERT(bytes <= groups_.anonymous(group));
    groups_.charge_anonymous(group, -bytes);
  }
  anonymous_ -= bytes;
  if (!nodes_.empty()) nodes_.release(bytes, nodes_.toucher(), &NodeUse::anonymous, [](NodeId, std::int64_t) {});
  settle();
  if (listeners_.progress) listeners_.progress();
}

std::int64_t dirty_and_writeback(const PageCache& cache) noexcept {
  const MemoryState memory = cache.memory();
  return memory.dirty + memory.writeback;
}

// --- Per file -------------------------------------------------------------------------------

PageCache::FileEntry& PageCache::file_entry(FileId file) {
  PC_ASSERT(file != kNoFile);
  if (file >= files_.size()) {
    files_.resize(static_cast<std::size_t>(file) + 1);
    writeback_.resize(files_.size());
  }
  return files_[file];
}

FileUse PageCache::file(FileId file) const noexcept {
  if (file >= files_.size()) return {};
  const FileEntry& entry = files_[file];
  return FileUse{.inactive = entry.inactive_bytes, .active = entry.active_bytes, .dirty = entry.dirty_bytes};
}

// --- Block bookkeeping: every list and counter changes here and only here -------------------

BlockId PageCache::new_block(FileId file, std::int64_t size, BlockState state, double now, NodeId node) {
  const BlockId id = blocks_.take();
  Block& block = blocks_[id];
  block.file = file;
  block.node = node;
  block.size = size;
  block.state = state;
  block.entry_time = now;
  return id;
}

void PageCache::append(BlockId id, ListKind kind, bool front) {
  const Block& block = blocks_[id];
  FileEntry& entry = file_entry(block.file);
  if (front) {
    list_of(kind).push_front(id);
    file_list(entry, kind).push_front(blocks_, id);
  } else {
    list_of(kind).push_back(id);
    file_list(entry, kind).push_back(blocks_, id);
  }
  on_dirty_linked(id);
  ++entry.blocks;
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += block.size;
  charge(block.file, block.node, block.size);
  if (block.state == BlockState::Dirty) entry.dirty_bytes += block.size;
  if (block.state == BlockState::Clean) on_clean_linked(id);
  else groups_.charge_dirty(block.file, block.size);
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
  charge(block.file, block.node, -block.size);
  if (block.state == BlockState::Dirty) entry.dirty_bytes -= block.size;
  if (block.state != BlockState::Clean) groups_.charge_dirty(block.file, -block.size);
}

bool PageCache::extend_tail(FileId file, std::int64_t bytes, Placement at, NodeId node) {
  const ListKind kind = at.list;
  // New clean data of the file at the most recently used end, right behind a clean block of
  // the same file in the same state: one block, not two. The bytes are in the same place on
  // the lists either way; a file read chunk by chunk then holds a block per run, not per
  // chunk, which bounds the number of blocks by the runs of data rather than the chunks.
  LruList& list = list_of(kind);
  const BlockId tail_id = list.back();
  if (tail_id == kNoBlock) return false;
  const Block& tail = blocks_[tail_id];
  if (tail.file != file || tail.state != BlockState::Clean || tail.referenced != at.referenced || tail.policy_bits != at.bits || tail.ranged ||
      tail.node != node) {
    return false;
  }
  list.resize(tail_id, tail.size + bytes);
  FileEntry& entry = files_[file];
  (kind == ListKind::Inactive ? entry.inactive_bytes : entry.active_bytes) += bytes;
  charge(file, node, bytes);
  return true;
}

void PageCache::destroy(BlockId id) {
  unlink(id);
  if (blocks_[id].state == BlockState::Dirty) dirty_by_age_.erase(blocks_, id);
  if (blocks_[id].state == BlockState::Writeback) writeback_[blocks_[id].file].erase(blocks_, id);
  if (blocks_[id].ranged) ranges_.erase(blocks_[id].file, id);
  blocks_[id].size = 0;  // no longer a block (a ReadCursor may still name it)
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
  if (was_clean != (state == BlockState::Clean)) groups_.charge_dirty(block.file, was_clean ? block.size : -block.size);
  if (was_clean && state != BlockState::Clean) on_clean_unlinked(id);
  if (block.state == BlockState::Writeback && state != BlockState::Writeback) {
    writeback_[block.file].erase(blocks_, id);
    block.entry_time = 0.0;  // no longer its write
  }
  list_of(block.list).set_state(id, state);
  if (!was_clean && state == BlockState::Clean) on_clean_linked(id);
}

void PageCache::start_writeback(BlockId id, std::uint64_t token) {
  set_state(id, BlockState::Writeback);
  blocks_[id].writeback_batch = token;  // no longer dirty: its entry time is not needed
  writeback_[blocks_[id].file].push_back(blocks_, id);  // off the dirty and clean lists: their links are free
}

void PageCache::link_clean(BlockId id) {
  const Block& block = blocks_[id];
  FileEntry& entry = files_[block.file];
  FileCleanOrder& clean = file_clean_list(entry, block.list);
  link_in_order(blocks_, file_list(entry, block.list), clean, id, [](const Block& b) { return b.state == BlockState::Clean; });
  // A higher key waits until the file comes to the top of reclaimable_ (see there).
  if (clean.front() == id && entry.writers == 0) mark_reclaimable(block.list, block.file, block.order);
}

void PageCache::mark_reclaimable(ListKind kind, FileId file, std::uint64_t key) {
  reclaimable(kind).lower(0, file, key);
  if (const GroupId group = groups_.of(file); group != kRootGroup) reclaimable(kind, true).lower(group, file, key);
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
  if (block.state == BlockState::Writeback) tail.writeback_batch = block.writeback_batch;
  else tail.entry_time = block.entry_time;
  tail.referenced = block.referenced;
  tail.policy_bits = block.policy_bits;
  tail.node = block.node;
  if (block.ranged) {
    tail.ranged = true;
    ranges_.insert(block.file, tail_id, ranges_.offset(id) + head_size, tail.size);
    ranges_.resize(block.file, id, head_size);
  }
  LruList& list = list_of(block.list);
  list.resize(id, head_size);
  list.insert_after(id, tail_id);
  on_dirty_linked(tail_id);
  FileEntry& entry = files_[block.file];
  file_list(entry, block.list).insert_after(blocks_, id, tail_id);
  ++entry.blocks;
  if (tail.state == BlockState::Dirty) dirty_by_age_.insert_after(blocks_, id, tail_id);
  if (tail.state == BlockState::Writeback) writeback_[block.file].insert_after(blocks_, id, tail_id);
  if (tail.state == BlockState::Clean && index_clean_) {
    file_clean_list(entry, block.list).insert_after(blocks_, id, tail_id);
  }
  // Per-file byte counters are unchanged: the file holds the same bytes in the same list.
  return id;
}

void PageCache::settle() {
  if (balance_always_) balance();
  if (checking_) check_after_operation();
  if (listeners_.free_memory) listeners_.free_memory(free(), anonymous_);
  if (listeners_.change) listeners_.change();
}

// --- Cache contents -------------------------------------------------------------------------

void PageCache::add_new(FileId file, std::int64_t bytes, BlockState state, double now, Placement at) {
  PC_ASSERT(bytes >= 0);
  if (bytes == 0) return;
  if (bytes > free()) {
    throw SimulationError(fmt::format("cannot cache {} bytes: only {} free", bytes, free()));
  }
  if (nodes_.empty()) {
    add_new_on(0, file, bytes, state, now, at);
  } else {
    nodes_.place(bytes, nodes_.toucher(), [&](NodeId node, std::int64_t part) {
      if (node != nodes_.toucher()) nodes_.remote().cache += part;
      add_new_on(node, file, part, state, now, at);
    });
  }
  settle();
}

// Inlined: on a one-node host it is add_new itself, the cache's most frequent mutation.
[[gnu::always_inline]] inline void PageCache::add_new_on(NodeId node, FileId file, std::int64_t bytes, BlockState state, double now, Placement at) {
  PC_ASSERT(state == BlockState::Clean || at.list == ListKind::Inactive);
  if (state == BlockState::Clean && extend_tail(file, bytes, at, node)) return;
  // A ranged file's data written whole goes after its last cached byte (ranged writes place
  // their own).
  const BlockId id =
      ranged(file) ? new_ranged_block(file, ranges_.file_end(file), bytes, state, now, node) : new_block(file, bytes, state, now, node);
  blocks_[id].referenced = at.referenced;
  set_policy_bits(blocks_[id], at.bits);
  append(id, at.list);
  if (state == BlockState::Dirty) {
    // Its place by age: the newest in a simulation, where time only goes forward; callers
    // that pass earlier times (tests) get it sorted in.
    BlockId after = dirty_by_age_.back();
    while (after != kNoBlock && blocks_[after].entry_time > now) after = DirtyOrder::prev(blocks_, after);
    if (after == kNoBlock) dirty_by_age_.push_front(blocks_, id);
    else dirty_by_age_.insert_after(blocks_, after, id);
  }
}

void PageCache::add_clean(FileId file, std::int64_t bytes, double now) { add_new(file, bytes, BlockState::Clean, now); }

void PageCache::add_read(FileId file, std::int64_t bytes, double now) {
  add_arriving(file, kNoOffset, bytes, now, true);
  if (bytes > 0) policy_->missed(*this, file, bytes);
}

void PageCache::add_arriving(FileId file, std::int64_t offset, std::int64_t bytes, double now, bool demand) {
  // The read that brought the data in is its first touch.
  if (!arrivals_) {
    const Placement at{.referenced = demand && first_touch_};
    return offset == kNoOffset ? add_new(file, bytes, BlockState::Clean, now, at) : place_ranged(file, offset, bytes, BlockState::Clean, now, at);
  }
  while (bytes > 0) {
    const Policy::Arrival part = policy_->arriving(*this, file, offset, bytes, demand);
    PC_ASSERT(part.bytes > 0 && part.bytes <= bytes);
    if (offset == kNoOffset) {
      add_new(file, part.bytes, BlockState::Clean, now, part.at);
    } else {
      place_ranged(file, offset, part.bytes, BlockState::Clean, now, part.at);
      offset += part.bytes;
    }
    bytes -= part.bytes;
  }
}

void PageCache::add_dirty(FileId file, std::int64_t bytes, double now) {
  add_new(file, bytes, BlockState::Dirty, now);
  totals_.peak_dirty = std::max(totals_.peak_dirty, dirty());
}

void PageCache::reserve(std::int64_t bytes) {
  PC_ASSERT(bytes >= 0);
  if (bytes > free()) throw SimulationError(fmt::format("cannot reserve {} bytes: only {} free", bytes, free()));
  reserved_ += bytes;
  if (!nodes_.empty()) {
    nodes_.place(bytes, nodes_.toucher(), [&](NodeId node, std::int64_t part) {
      nodes_[node].reserved += part;
      if (node != nodes_.toucher()) nodes_.remote().reserved += part;
    });
  }
  settle();
}

void PageCache::commit_dirty(FileId file, std::int64_t bytes, double now, std::int64_t offset) {
  PC_ASSERT(bytes >= 0 && bytes <= reserved_);
  PC_ASSERT_MSG(offset == kNoOffset || ranged(file), "an offset is written in a file held by range");
  reserved_ -= bytes;
  if (offset != kNoOffset) {
    // The pages reserved are freed and taken again where write_range places the holes.
    if (!nodes_.empty()) nodes_.release(bytes, nodes_.toucher(), &NodeUse::reserved, [](NodeId, std::int64_t) {});
    write_range(file, offset, bytes, now);
  } else if (nodes_.empty()) {
    add_dirty(file, bytes, now);
  } else {
    // The pages the copy filled: its reservation's, on their nodes.
    nodes_.release(bytes, nodes_.toucher(), &NodeUse::reserved,
                   [&](NodeId node, std::int64_t part) { add_new_on(node, file, part, BlockState::Dirty, now, {}); });
    totals_.peak_dirty = std::max(totals_.peak_dirty, dirty());
    settle();
  }
  if (listeners_.progress) listeners_.progress();
}

}  // namespace pagecache::cache
