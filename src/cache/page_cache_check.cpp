// PageCache: its invariants recomputed from the blocks (tests, debug builds).

#include "cache/page_cache.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace pagecache::cache {

void PageCache::check_after_operation() {
  constexpr std::size_t kSpread = 4;  // at most 4 block visits per operation, amortised
  if (amortised_ && ++unchecked_operations_ * kSpread < blocks_.in_use()) return;
  unchecked_operations_ = 0;
  check_invariants();
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
  for (std::size_t f = 0; f < files_.size(); ++f) blocks_in_files += check_file(f, most);
  PC_ASSERT_MSG(blocks_in_files == inactive_.size() + active_.size(), "a block is missing from its file's list");
  if (!groups_.empty()) check_groups();
  check_nodes();
  PC_ASSERT(target_ == kAnyGroup);
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    // The groups' heaps are checked by groups_.check(); here only that none is kept needlessly.
    reclaimable_[static_cast<std::size_t>(kind)].check();
    for (const FileHeaps* files : {&reclaimable_[static_cast<std::size_t>(kind)], &groups_.reclaimable(kind)}) {
      for (std::size_t h = 0; h < files->heaps(); ++h) PC_ASSERT(index_clean_ || files->empty(h));
    }
  }
  check_dirty_by_age(most);
  if (expiry_scan_.after != kNoBlock) check_expiry_scan();
}

std::size_t PageCache::check_file(std::size_t f, std::size_t most) const {
  const FileEntry& entry = files_[f];
  std::int64_t bytes[2] = {0, 0};
  std::int64_t dirty_bytes = 0;
  std::size_t blocks = 0;
  std::size_t in_writeback = 0;
  for (ListKind kind : {ListKind::Inactive, ListKind::Active}) {
    const FileOrder& flist = kind == ListKind::Inactive ? entry.inactive : entry.active;
    // Its clean list holds its clean blocks in the list, in order; and its place in
    // reclaimable_.
    const FileCleanOrder& clean = kind == ListKind::Inactive ? entry.clean_inactive : entry.clean_active;
    auto clean_it = clean.range(blocks_).begin();
    const auto clean_end = clean.range(blocks_).end();
    if (index_clean_) {
      for (const Block& b : flist.range(blocks_)) {
        if (b.state != BlockState::Clean) continue;
        PC_ASSERT_MSG(clean_it != clean_end && &*clean_it == &b, fmt::format("file {}: clean list out of order", f));
        ++clean_it;
      }
    }
    PC_ASSERT_MSG(clean_it == clean_end, fmt::format("file {}: a block on its clean list in error", f));
    if (!clean.empty() && entry.writers == 0) {
      const auto file = static_cast<FileId>(f);
      const FileHeaps& files = reclaimable_[static_cast<std::size_t>(kind)];
      PC_ASSERT_MSG(files.contains(file) && files.key(0, file) <= blocks_[clean.front()].order,
                    fmt::format("file {} missing from the reclaimable files, or its key too high", f));
      // And in its group's heap, for the group's own reclaim.
      if (const GroupId group = groups_.of(file); group != kRootGroup) {
        const FileHeaps& own = groups_.reclaimable(kind);
        PC_ASSERT_MSG(own.contains(file) && own.key(group, file) <= blocks_[clean.front()].order,
                      fmt::format("file {} missing from its group's reclaimable files, or its key too high", f));
      }
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
      if (b.state == BlockState::Writeback) ++in_writeback;
      ++blocks;
    }
  }
  PC_ASSERT_MSG(bytes[0] == entry.inactive_bytes && bytes[1] == entry.active_bytes,
                fmt::format("file {} byte counters disagree with its blocks", f));
  PC_ASSERT(dirty_bytes == entry.dirty_bytes);
  PC_ASSERT_MSG(entry.blocks == blocks, fmt::format("file {}: block count disagrees with its lists", f));
  // Its list of blocks in writeback holds exactly those.
  std::size_t listed = 0;
  for (const Block& b : writeback_[f].range(blocks_)) {
    PC_ASSERT_MSG(listed < most, fmt::format("file {}: its writeback list holds more blocks than there are (a cycle?)", f));
    PC_ASSERT_MSG(b.file == f && b.state == BlockState::Writeback, fmt::format("file {}: a block on its writeback list in error", f));
    ++listed;
  }
  PC_ASSERT_MSG(listed == in_writeback, fmt::format("file {}: {} blocks in writeback, {} on its list", f, in_writeback, listed));
  check_ranges(f, most);
  return blocks;
}

// Each group's charges are its files' cached bytes and its anonymous memory.
void PageCache::check_groups() const {
  std::vector<std::int64_t> charged(groups_.size(), 0);
  std::vector<std::int64_t> unclean(groups_.size(), 0);
  for (std::size_t f = 0; f < files_.size(); ++f) {
    const auto file = static_cast<FileId>(f);
    charged[groups_.of(file)] += cached(file);
    unclean[groups_.of(file)] += dirty(file) + writeback(file);
  }
  groups_.check(charged, unclean, anonymous_);
}

void PageCache::check_dirty_by_age(std::size_t most) const {
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
}

// Where the expiry search resumes: a dirty block, with no expired block before it.
void PageCache::check_expiry_scan() const {
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

}  // namespace pagecache::cache
