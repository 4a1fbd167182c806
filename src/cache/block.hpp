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
//    (their entry times), so that the flusher sees in O(1) whether anything has expired.

#include <boost/intrusive/list.hpp>

#include <cstdint>

namespace pagecache::cache {

using FileId = std::uint32_t;

enum class BlockState : std::uint8_t { Clean, Dirty, Writeback };
enum class ListKind : std::uint8_t { Inactive, Active };

using SafeHook = boost::intrusive::list_member_hook<boost::intrusive::link_mode<boost::intrusive::safe_link>>;

struct Block {
  FileId file = 0;
  std::int64_t size = 0;
  double last_access = 0.0;
  double entry_time = 0.0;  // when the data became dirty; expiry is measured from it
  BlockState state = BlockState::Clean;
  ListKind list = ListKind::Inactive;
  bool referenced = false;          // touched once while inactive (two-touch activation)
  std::uint64_t writeback_batch = 0;  // the flush that is writing it (state Writeback)

  SafeHook lru_hook;
  SafeHook state_hook;
  SafeHook file_hook;
  SafeHook dirty_hook;
};

template <SafeHook Block::*Hook>
using BlockList = boost::intrusive::list<
    Block, boost::intrusive::member_hook<Block, SafeHook, Hook>, boost::intrusive::constant_time_size<true>>;

using LruOrder = BlockList<&Block::lru_hook>;
using StateOrder = BlockList<&Block::state_hook>;
using FileOrder = BlockList<&Block::file_hook>;
using DirtyOrder = BlockList<&Block::dirty_hook>;

}  // namespace pagecache::cache
