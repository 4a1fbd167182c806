#pragma once
// Block: a run of one file's cached bytes touched by one I/O operation (the paper's "data
// block"). Blocks live in PageCache's BlockPool, named by their BlockId, and are linked into
// these lists (BlockList), by id:
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
//    being written finds a file's least recently used clean block at once; while in
//    writeback, its file's blocks in writeback, so that the end of a write finds its blocks
//    without walking the file's others. In writeback its entry time's bytes hold the write
//    it belongs to.
// Its `order` places it in its LRU list: a block appended gets a key above every other's in
// that list, and the tail of a split (inserted right after its head, the only insertion not
// at the end) takes its head's. Keys therefore never decrease along a list, and blocks with
// equal keys are the pieces of one appended block: contiguous, of one file.
//
// A block fits one cache line (64 bytes; links are 32-bit ids): blocks are most of a large
// simulation's memory and of what a chunk operation touches. page_cache_bench reports its size.

#include <cstdint>
#include <limits>

namespace pagecache::cache {

using FileId = std::uint32_t;
using BlockId = std::uint32_t;
inline constexpr BlockId kNoBlock = std::numeric_limits<BlockId>::max();
/// Memory is handed out, and a file held by range is cached and freed, in pages.
inline constexpr std::int64_t kPageSize = 4096;

enum class BlockState : std::uint8_t { Clean, Dirty, Writeback };
enum class ListKind : std::uint8_t { Inactive, Active };
/// The largest value Block::policy_bits holds.
inline constexpr std::uint8_t kMaxPolicyBits = 63;

/// Where new data goes and how it is marked: the MRU end of `list`, with `referenced` and the
/// policy's bits (Policy::arriving).
struct Placement {
  ListKind list = ListKind::Inactive;
  bool referenced = false;
  std::uint8_t bits = 0;
};

/// A block's neighbours on one of its lists (kNoBlock: none; both kNoBlock while unlinked,
/// or while the only member).
struct BlockLinks {
  BlockId prev = kNoBlock;
  BlockId next = kNoBlock;
};

struct alignas(64) Block {
  BlockLinks lru;       // its LRU list
  BlockLinks by_state;  // its LRU list's sub-list of the blocks in its state
  BlockLinks in_file;   // its file's list for its LRU list
  // Dirty: the dirty blocks by age; clean: its file's clean sub-list; in writeback: its
  // file's blocks in writeback.
  BlockLinks state_list;
  std::int64_t size = 0;
  union {
    double entry_time = 0.0;        // when the data became dirty; expiry is measured from it
    std::uint64_t writeback_batch;  // in writeback: the flush that is writing it
  };
  std::uint64_t order = 0;  // its place in its LRU list (see above)
  FileId file = 0;
  BlockState state = BlockState::Clean;
  ListKind list = ListKind::Inactive;
  bool referenced : 1 = false;    // touched once while inactive (two-touch activation)
  bool ranged : 1 = false;        // of a file held by byte range: indexed in PageCache's FileRanges
  std::uint8_t policy_bits : 6 = 0;  // the policy's own marks (Placement::bits): split with the block, merged only if equal
  std::uint8_t node = 0;        // the NUMA node its memory is on (docs/model.md §6.20)
};
static_assert(sizeof(Block) == 64, "a block fills one cache line");

/// Sets a block's policy bits (the low six bits of `bits`).
inline void set_policy_bits(Block& block, std::uint8_t bits) noexcept { block.policy_bits = bits & kMaxPolicyBits; }

}  // namespace pagecache::cache
