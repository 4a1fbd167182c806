#pragma once
// MemoryState: one host's memory at an instant, in bytes (docs/model.md §1).
//   total = free + anonymous + cached + reserved,  cached = active + inactive,
//   dirty + writeback <= cached.
// `reserved` is memory taken for copies in flight into the page cache: a chunk being written
// holds its pages from the start of its memory transfer, and joins `cached` (as a dirty
// block) when the transfer ends. It is zero between I/O operations.

#include <cstdint>

namespace pagecache {

struct MemoryState {
  std::int64_t total = 0;
  std::int64_t free = 0;
  std::int64_t anonymous = 0;  ///< application buffers
  std::int64_t cached = 0;     ///< page cache
  std::int64_t dirty = 0;      ///< cached data not yet written to its device
  std::int64_t writeback = 0;  ///< cached data being written to its device
  std::int64_t active = 0;     ///< cached data on the active list
  std::int64_t inactive = 0;   ///< cached data on the inactive list
  std::int64_t reserved = 0;   ///< pages being filled by transfers in flight
  friend bool operator==(const MemoryState&, const MemoryState&) = default;
};

}  // namespace pagecache
