#include "cache/file_ranges.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

void FileRanges::split(BlockId t, std::int64_t offset, BlockId& less, BlockId& rest) noexcept {
  // Down one path: each node goes to the side of `offset` it is on, keeping the other subtree.
  BlockId* less_hole = &less;
  BlockId* rest_hole = &rest;
  while (t != kNoBlock) {
    Node& n = nodes_[t];
    if (n.offset < offset) {
      *less_hole = t;
      less_hole = &n.right;
      t = n.right;
    } else {
      *rest_hole = t;
      rest_hole = &n.left;
      t = n.left;
    }
  }
  *less_hole = kNoBlock;
  *rest_hole = kNoBlock;
}

BlockId FileRanges::merge(BlockId a, BlockId b) noexcept {
  BlockId joined = kNoBlock;
  BlockId* hole = &joined;
  while (a != kNoBlock && b != kNoBlock) {
    if (above(a, b)) {
      *hole = a;
      hole = &nodes_[a].right;
      a = nodes_[a].right;
    } else {
      *hole = b;
      hole = &nodes_[b].left;
      b = nodes_[b].left;
    }
  }
  *hole = a != kNoBlock ? a : b;
  return joined;
}

void FileRanges::insert(FileId file, BlockId block, std::int64_t offset) {
  if (block >= nodes_.size()) nodes_.resize(std::max<std::size_t>(2 * nodes_.size(), std::size_t{block} + 1));
  if (file >= roots_.size()) roots_.resize(std::max<std::size_t>(2 * roots_.size(), std::size_t{file} + 1), kNoBlock);
  Node& node = nodes_[block];
  node.offset = offset;
  // Down to the first node the new one ranks above; the subtree there splits under it.
  BlockId* link = &roots_[file];
  while (*link != kNoBlock && above(*link, block)) {
    Node& n = nodes_[*link];
    PC_ASSERT_MSG(n.offset != offset, fmt::format("file {}: two blocks at offset {}", file, offset));
    link = offset < n.offset ? &n.left : &n.right;
  }
  split(*link, offset, node.left, node.right);  // a duplicate below here: check() finds it
  *link = block;
}

void FileRanges::erase(FileId file, BlockId block) {
  const std::int64_t offset = nodes_[block].offset;
  BlockId* link = &roots_[file];
  while (*link != block) {
    PC_ASSERT_MSG(*link != kNoBlock, fmt::format("file {}: block {} is not indexed", file, block));
    link = offset < nodes_[*link].offset ? &nodes_[*link].left : &nodes_[*link].right;
  }
  Node& node = nodes_[block];
  *link = merge(node.left, node.right);
  node.left = node.right = kNoBlock;
}

BlockId FileRanges::floor(FileId file, std::int64_t offset) const noexcept {
  BlockId found = kNoBlock;
  for (BlockId t = root(file); t != kNoBlock;) {
    if (nodes_[t].offset <= offset) {
      found = t;
      t = nodes_[t].right;
    } else {
      t = nodes_[t].left;
    }
  }
  return found;
}

FileRanges::Around FileRanges::around(FileId file, std::int64_t offset) const noexcept {
  Around found;
  for (BlockId t = root(file); t != kNoBlock;) {
    if (nodes_[t].offset <= offset) {
      found.floor = t;
      t = nodes_[t].right;
    } else {
      found.above = t;
      t = nodes_[t].left;
    }
  }
  return found;
}

BlockId FileRanges::ceiling(FileId file, std::int64_t offset) const noexcept {
  BlockId found = kNoBlock;
  for (BlockId t = root(file); t != kNoBlock;) {
    if (nodes_[t].offset >= offset) {
      found = t;
      t = nodes_[t].left;
    } else {
      t = nodes_[t].right;
    }
  }
  return found;
}

BlockId FileRanges::next(FileId file, BlockId block) const noexcept {
  const std::int64_t offset = nodes_[block].offset;
  // No parent links: the successor is the last node left of on the way down, or the leftmost
  // node of the right subtree.
  if (BlockId t = nodes_[block].right; t != kNoBlock) {
    while (nodes_[t].left != kNoBlock) t = nodes_[t].left;
    return t;
  }
  BlockId found = kNoBlock;
  for (BlockId t = root(file); t != block && t != kNoBlock;) {
    if (offset < nodes_[t].offset) {
      found = t;
      t = nodes_[t].left;
    } else {
      t = nodes_[t].right;
    }
  }
  return found;
}

std::size_t FileRanges::check(FileId file, std::size_t most) const {
  std::size_t seen = 0;
  return check_subtree(root(file), kLowest, std::numeric_limits<std::int64_t>::max(), most, seen);
}

std::size_t FileRanges::check_subtree(BlockId t, std::int64_t low, std::int64_t high, std::size_t most, std::size_t& seen) const {
  if (t == kNoBlock) return 0;
  PC_ASSERT_MSG(++seen <= most, "a file's offset index holds more nodes than there are blocks (a cycle?)");
  const Node& n = nodes_[t];
  PC_ASSERT_MSG(n.offset >= low && n.offset <= high, fmt::format("block {}: offset {} out of order", t, n.offset));
  PC_ASSERT_MSG(n.left == kNoBlock || above(t, n.left), "offset index out of heap order");
  PC_ASSERT_MSG(n.right == kNoBlock || above(t, n.right), "offset index out of heap order");
  const std::size_t left = check_subtree(n.left, low, n.offset - 1, most, seen);
  return left + 1 + check_subtree(n.right, n.offset + 1, high, most, seen);
}

}  // namespace pagecache::cache
