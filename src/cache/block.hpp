#pragma once
// Block: a run of one file's cached bytes touched by one I/O operation (the paper's "data
// block"). Blocks are owned by PageCache's pool and linked into three intrusive lists:
//  - its LRU list (inactive or active), in LRU order (front = least recently used);
//  - the sub-list of that LRU list holding the blocks in the same state (clean, dirty,
//    writeback), in the same relative order, so flushing finds dirty data and eviction finds
//    clean data without walking past the others;
//  - its file's list for that LRU list, in the same relative order, so that per-file queries
//    and re-accesses cost O(blocks of the file);
//  - while dirty, the page cache's list of dirty blocks in the order they became dirty
//    (their entry times), so that the flusher sees in O(1) whether anything has expired;
//    while clean, with protect_files_being_written, the sub-list of its file's list holding
//    the file's clean blocks, in the same relative order, so that eviction sparing the files
//    being written finds a file's least recently used clean block at once. (One hook for
//    both: a block is never dirty and clean at once, and a Block fits in 112 bytes.)
// Its `order` places it in its LRU list: a block appended gets a key above every other's in
// that list, and the tail of a split (inserted right after its head, the only insertion not
// at the end) takes its head's. Keys therefore never decrease along a list, and blocks with
// equal keys are the pieces of one appended block: contiguous, of one file.

#include <boost/intrusive/list.hpp>

#include <cstdint>

namespace pagecache::cache {

using FileId = std::uint32_t;

enum class BlockState : std::uint8_t { Clean, Dirty, Writeback };
enum class ListKind : std::uint8_t { Inactive, Active };

using SafeHook = boost::intrusive::list_member_hook<boost::intrusive::link_mode<boost::intrusive::safe_link>>;

struct Block {
  FileId file = 0;
  BlockState state = BlockState::Clean;
  ListKind list = ListKind::Inactive;
  bool referenced = false;  // touched once while inactive (two-touch activation)
  std::int64_t size = 0;
  double last_access = 0.0;
  double entry_time = 0.0;            // when the data became dirty; expiry is measured from it
  std::uint64_t writeback_batch = 0;  // the flush that is writing it (state Writeback)
  std::uint64_t order = 0;            // its place in its LRU list (see above)

  SafeHook lru_hook;
  SafeHook state_hook;
  SafeHook file_hook;
  SafeHook dirty_or_clean_hook;
};

template <SafeHook Block::*Hook>
using BlockList = boost::intrusive::list<
    Block, boost::intrusive::member_hook<Block, SafeHook, Hook>, boost::intrusive::constant_time_size<true>>;

using LruOrder = BlockList<&Block::lru_hook>;
using StateOrder = BlockList<&Block::state_hook>;
// No size counter: a file's entry keeps its block count beside its byte counters, in one cache
// line (see PageCache::FileEntry).
using FileOrder = boost::intrusive::list<Block, boost::intrusive::member_hook<Block, SafeHook, &Block::file_hook>,
                                         boost::intrusive::constant_time_size<false>>;
// Only its front is asked for: no size counter, which keeps a file's entry small.
using FileCleanOrder = boost::intrusive::list<Block, boost::intrusive::member_hook<Block, SafeHook, &Block::dirty_or_clean_hook>,
                                              boost::intrusive::constant_time_size<false>>;
using DirtyOrder = BlockList<&Block::dirty_or_clean_hook>;

}  // namespace pagecache::cache
