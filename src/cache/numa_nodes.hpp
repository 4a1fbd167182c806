#pragma once
// NumaNodes: a host's memory split among its NUMA nodes (docs/model.md §6.20), and where new
// memory goes. Per node: its size and the application memory, cache and reservations on it.
// A one-node host has none of this: PageCache keeps the table empty and pays nothing.
//
// Placement is the kernel's default policy with zone_reclaim_mode 0 (mm/page_alloc.c,
// get_page_from_freelist over the zonelist): the toucher's node first, then the others in
// order, each as far as its free memory goes; nothing is reclaimed while a node has free memory.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pagecache::cache {

using NodeId = std::uint8_t;
/// As a reclaim target: every node.
inline constexpr NodeId kAnyNode = 0xff;
/// The most nodes a host may have: a copy has one other node its pages may be on.
inline constexpr int kMaxNodes = 2;

/// One node's memory.
struct NodeUse {
  std::int64_t total = 0;
  std::int64_t anonymous = 0;
  std::int64_t cached = 0;
  std::int64_t reserved = 0;
  std::int64_t free() const noexcept { return total - anonymous - cached - reserved; }
};

/// Bytes that threads placed, or read from the cache, on another node than their own, so far:
/// the I/O controller takes differences around an operation to price its copies, as it does
/// with cold memory.
struct RemoteTally {
  std::int64_t cache = 0;      ///< new cache data
  std::int64_t anonymous = 0;  ///< application memory
  std::int64_t reserved = 0;   ///< pages taken for a copy into the cache
  std::int64_t reread = 0;     ///< cached data re-accessed by a read
};

class NumaNodes {
 public:
  /// The nodes modelled: 1 on a host whose table is empty.
  std::size_t count() const noexcept { return std::max<std::size_t>(nodes_.size(), 1); }
  /// The node of the thread whose operations follow (0 until set): they take new memory there
  /// first (place), give memory back there first, and read the cache from there.
  NodeId toucher() const noexcept { return toucher_; }
  void touch_from(NodeId node) noexcept { toucher_ = node; }
  /// What threads placed, or read from the cache, on another node than their own, so far.
  const RemoteTally& remote() const noexcept { return remote_; }
  RemoteTally& remote() noexcept { return remote_; }

  /// `count` nodes sharing `total` bytes evenly (the first ones take the remainder).
  void split(std::int64_t total, int count) {
    nodes_.assign(static_cast<std::size_t>(count), NodeUse{});
    for (int i = 0; i < count; ++i) nodes_[static_cast<std::size_t>(i)].total = total / count + (i < total % count ? 1 : 0);
  }
  bool empty() const noexcept { return nodes_.empty(); }
  std::size_t size() const noexcept { return nodes_.size(); }
  NodeUse& operator[](NodeId node) noexcept { return nodes_[node]; }
  const NodeUse& operator[](NodeId node) const noexcept { return nodes_[node]; }

  /// Calls `take(node, bytes)` for each part of `bytes` of new memory of a thread on `toucher`:
  /// its node as far as its free memory goes, then the next nodes in order. Every part is > 0;
  /// the caller has checked that the nodes have `bytes` free together.
  template <class Take>
  void place(std::int64_t bytes, NodeId toucher, Take&& take) const {
    for (std::size_t i = 0; i < nodes_.size() && bytes > 0; ++i) {
      const auto node = static_cast<NodeId>((toucher + i) % nodes_.size());
      const std::int64_t part = std::min(bytes, nodes_[node].free());
      if (part <= 0) continue;
      take(node, part);
      bytes -= part;
    }
  }
  /// Calls `give(node, bytes)` for each part of `bytes` of what `held` counts (application
  /// memory, reservations) given back by a thread on `toucher`: its node first, then the next.
  /// Which pages of a buffer are where is not kept; a thread's memory is mostly on its node.
  template <class Give>
  void release(std::int64_t bytes, NodeId toucher, std::int64_t NodeUse::*held, Give&& give) {
    for (std::size_t i = 0; i < nodes_.size() && bytes > 0; ++i) {
      const auto node = static_cast<NodeId>((toucher + i) % nodes_.size());
      const std::int64_t part = std::min(bytes, nodes_[node].*held);
      if (part <= 0) continue;
      nodes_[node].*held -= part;
      give(node, part);
      bytes -= part;
    }
  }

  /// Throws InvariantError unless each node's cache is `cached_on[node]` (its blocks' sum), no
  /// node holds more than it has, and the nodes add up to `host`.
  void check(const std::int64_t* cached_on, const NodeUse& host) const;

 private:
  std::vector<NodeUse> nodes_;
  NodeId toucher_ = 0;
  RemoteTally remote_;
};

}  // namespace pagecache::cache
