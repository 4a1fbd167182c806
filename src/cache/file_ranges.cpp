#include "cache/file_ranges.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

namespace {

// How many of the first `count` keys are <= key (upper bound's position), by a full scan: a
// node's keys are four cache lines, fetched together when scanned in order, where a binary
// search waits for each line it probes in turn.
int keys_at_or_below(const std::int64_t* keys, int count, std::int64_t key) noexcept {
  int n = 0;
  for (int i = 0; i < count; ++i) n += keys[i] <= key ? 1 : 0;
  return n;
}

// How many are < key (lower bound's position).
int keys_below(const std::int64_t* keys, int count, std::int64_t key) noexcept {
  int n = 0;
  for (int i = 0; i < count; ++i) n += keys[i] < key ? 1 : 0;
  return n;
}

}  // namespace

void FileRanges::fetch(NodeId n) const noexcept {
  // Every line of the node at once: a visit then waits for one miss, not for one per line
  // (the count, then the keys it scans, then the id and end it picks).
  const char* p = reinterpret_cast<const char*>(&nodes_[n]);
  for (std::size_t line = 0; line < sizeof(Node); line += 64) __builtin_prefetch(p + line);
}

int FileRanges::child_for(const Node& n, std::int64_t key) const noexcept {
  // The last child whose least key is <= key; child 0 takes everything below keys[1].
  return keys_at_or_below(n.keys + 1, n.count - 1, key);
}

FileRanges::NodeId FileRanges::edge_leaf(FileId file, bool rightmost) const noexcept {
  NodeId n = tree(file).root;
  while (n != kNoNode && !nodes_[n].leaf) n = nodes_[n].ids[rightmost ? nodes_[n].count - 1 : 0];
  return n;
}

FileRanges::NodeId FileRanges::leaf_for(FileId file, std::int64_t offset) const noexcept {
  const Finger& f = finger_;
  if (f.leaf != kNoNode && f.file == file && f.splits == splits_ && nodes_[f.leaf].generation == f.generation && offset >= f.low &&
      offset < f.high) {
    return f.leaf;
  }
  NodeId n = tree(file).root;
  if (n == kNoNode) return kNoNode;
  std::int64_t low = std::numeric_limits<std::int64_t>::min();
  std::int64_t high = std::numeric_limits<std::int64_t>::max();
  fetch(n);
  while (!nodes_[n].leaf) {
    const Node& inner = nodes_[n];
    const int child = child_for(inner, offset);
    if (child > 0) low = inner.keys[child];
    if (child + 1 < inner.count) high = inner.keys[child + 1];
    n = inner.ids[child];
    fetch(n);
  }
  finger_ = Finger{.file = file, .leaf = n, .generation = nodes_[n].generation, .splits = splits_, .low = low, .high = high};
  return n;
}

void FileRanges::prefetch_leaf(FileId file, BlockId block) const noexcept {
  const Tree& t = tree(file);
  NodeId n = t.root;
  if (n == kNoNode) return;
  // By the height, not the nodes' kind: reading the leaf's would wait for it.
  for (int level = t.height - 1; level > 0; --level) n = nodes_[n].ids[child_for(nodes_[n], spans_[block].offset)];
  fetch(n);
}

void FileRanges::free_node(NodeId n) {
  ++nodes_[n].generation;
  free_nodes_.push_back(n);
}

FileRanges::Around FileRanges::around(FileId file, std::int64_t offset) const noexcept {
  const NodeId n = leaf_for(file, offset);
  if (n == kNoNode) return {};
  const Node& leaf = nodes_[n];
  const int pos = keys_at_or_below(leaf.keys, leaf.count, offset);
  Around found;
  // A leaf's least key may be above `offset` (its lower entries erased): the floor is then the
  // previous leaf's last entry; likewise the next leaf's first is the one above.
  const auto entry = [](const Node& node, int i) { return Located{node.ids[i], node.keys[i], node.ends[i]}; };
  if (pos > 0) found.floor = entry(leaf, pos - 1);
  else if (leaf.prev != kNoNode) found.floor = entry(nodes_[leaf.prev], nodes_[leaf.prev].count - 1);
  if (pos < leaf.count) found.above = entry(leaf, pos);
  else if (leaf.next != kNoNode) found.above = entry(nodes_[leaf.next], 0);
  return found;
}

BlockId FileRanges::ceiling(FileId file, std::int64_t offset) const noexcept {
  const Around at = around(file, offset);
  return at.floor.id != kNoBlock && at.floor.offset == offset ? at.floor.id : at.above.id;
}

BlockId FileRanges::first(FileId file) const noexcept {
  const NodeId n = edge_leaf(file, false);
  return n == kNoNode ? kNoBlock : nodes_[n].ids[0];
}

BlockId FileRanges::last(FileId file) const noexcept {
  const NodeId n = edge_leaf(file, true);
  return n == kNoNode ? kNoBlock : nodes_[n].ids[nodes_[n].count - 1];
}

FileRanges::NodeId FileRanges::new_node(bool leaf) {
  NodeId id;
  if (!free_nodes_.empty()) {
    id = free_nodes_.back();
    free_nodes_.pop_back();
  } else {
    id = static_cast<NodeId>(nodes_.size());
    nodes_.emplace_back();
  }
  const std::uint32_t generation = nodes_[id].generation;
  nodes_[id] = Node{};
  nodes_[id].generation = generation;
  nodes_[id].leaf = leaf;
  return id;
}

FileRanges::Split FileRanges::split_node(NodeId n) {
  ++splits_;
  const NodeId right = new_node(nodes_[n].leaf);  // may move nodes_: no reference held across it
  Node& l = nodes_[n];
  Node& r = nodes_[right];
  const int keep = l.count / 2;
  r.count = static_cast<std::uint16_t>(l.count - keep);
  std::copy(l.keys + keep, l.keys + l.count, r.keys);
  std::copy(l.ids + keep, l.ids + l.count, r.ids);
  if (l.leaf) std::copy(l.ends + keep, l.ends + l.count, r.ends);
  l.count = static_cast<std::uint16_t>(keep);
  if (l.leaf) {
    r.prev = n;
    r.next = l.next;
    if (l.next != kNoNode) nodes_[l.next].prev = right;
    l.next = right;
  }
  return {r.keys[0], right};
}

FileRanges::Split FileRanges::insert_below(NodeId n, int level, std::int64_t key, std::int64_t end, BlockId block) {
  int pos = 0;
  std::uint32_t id = block;
  if (level == 0) {
    const Node& leaf = nodes_[n];
    pos = keys_below(leaf.keys, leaf.count, key);
    PC_ASSERT_MSG(pos == leaf.count || leaf.keys[pos] != key, fmt::format("two blocks at offset {}", key));
  } else {
    const int child = child_for(nodes_[n], key);
    fetch(nodes_[n].ids[child]);
    const Split below = insert_below(nodes_[n].ids[child], level - 1, key, end, block);
    if (below.node == kNoNode) return {};
    key = below.key;
    id = below.node;
    pos = child + 1;
  }
  Split split;
  if (nodes_[n].count == kFan) {
    split = split_node(n);
    if (pos > nodes_[n].count) {
      pos -= nodes_[n].count;
      n = split.node;
    }
  }
  Node& node = nodes_[n];
  std::copy_backward(node.keys + pos, node.keys + node.count, node.keys + node.count + 1);
  std::copy_backward(node.ids + pos, node.ids + node.count, node.ids + node.count + 1);
  node.keys[pos] = key;
  node.ids[pos] = id;
  if (node.leaf) {
    std::copy_backward(node.ends + pos, node.ends + node.count, node.ends + node.count + 1);
    node.ends[pos] = end;
  }
  ++node.count;
  // An entry put first in the right half is that half's least key.
  if (split.node == n && pos == 0) split.key = key;
  return split;
}

void FileRanges::insert(FileId file, BlockId block, std::int64_t offset, std::int64_t size) {
  if (block >= spans_.size()) spans_.resize(std::max<std::size_t>(2 * spans_.size(), std::size_t{block} + 1));
  if (file >= trees_.size()) trees_.resize(std::max<std::size_t>(2 * trees_.size(), std::size_t{file} + 1));
  spans_[block] = {offset, offset + size};
  Tree& t = trees_[file];
  if (t.root == kNoNode) {
    t.root = new_node(true);
    t.height = 1;
  }
  // Into the finger's leaf if it holds the offset and has room: no descent, no separator moves.
  const Finger& f = finger_;
  if (f.leaf != kNoNode && f.file == file && f.splits == splits_ && nodes_[f.leaf].generation == f.generation && offset >= f.low &&
      offset < f.high && nodes_[f.leaf].count < kFan) {
    insert_below(f.leaf, 0, offset, offset + size, block);
    return;
  }
  const Split split = insert_below(t.root, t.height - 1, offset, offset + size, block);
  if (split.node == kNoNode) return;
  // The root split: a new root above both halves.
  const NodeId root = new_node(false);
  Node& r = nodes_[root];
  r.ids[0] = trees_[file].root;
  r.ids[1] = split.node;
  r.keys[1] = split.key;
  r.count = 2;
  trees_[file].root = root;
  ++trees_[file].height;
}

void FileRanges::resize(FileId file, BlockId block, std::int64_t size) noexcept {
  Span& span = spans_[block];
  span.end = span.offset + size;
  Node& leaf = nodes_[leaf_for(file, span.offset)];
  const int pos = keys_below(leaf.keys, leaf.count, span.offset);
  PC_ASSERT(pos < leaf.count && leaf.ids[pos] == block);
  leaf.ends[pos] = span.end;
}

bool FileRanges::erase_below(NodeId n, int level, std::int64_t key, BlockId block, bool is_root) {
  int pos = 0;
  if (level == 0) {
    const Node& leaf = nodes_[n];
    pos = keys_below(leaf.keys, leaf.count, key);
    PC_ASSERT_MSG(pos < leaf.count && leaf.ids[pos] == block, fmt::format("block {} is not indexed at offset {}", block, key));
  } else {
    pos = child_for(nodes_[n], key);
    fetch(nodes_[n].ids[pos]);
    if (!erase_below(nodes_[n].ids[pos], level - 1, key, block, false)) return false;
  }
  Node& node = nodes_[n];
  std::copy(node.keys + pos + 1, node.keys + node.count, node.keys + pos);
  std::copy(node.ids + pos + 1, node.ids + node.count, node.ids + pos);
  if (node.leaf) std::copy(node.ends + pos + 1, node.ends + node.count, node.ends + pos);
  --node.count;
  if (node.count > 0 || is_root) return node.count == 0;
  if (node.leaf) {
    if (node.prev != kNoNode) nodes_[node.prev].next = node.next;
    if (node.next != kNoNode) nodes_[node.next].prev = node.prev;
  }
  free_node(n);
  return true;
}

void FileRanges::erase(FileId file, BlockId block) {
  Tree& t = trees_[file];
  PC_ASSERT_MSG(t.root != kNoNode, fmt::format("file {}: block {} is not indexed", file, block));
  if (erase_below(t.root, t.height - 1, spans_[block].offset, block, true)) {
    free_node(t.root);
    t = Tree{};
    return;
  }
  // A root with one child gives way to it.
  while (t.height > 1 && nodes_[t.root].count == 1) {
    free_node(t.root);
    t.root = nodes_[t.root].ids[0];
    --t.height;
  }
}

std::int64_t FileRanges::cached_in(FileId file, std::int64_t offset, std::int64_t bytes) const noexcept {
  PC_ASSERT(tracked(file) && offset >= 0 && bytes >= 0);
  const std::int64_t end = offset + bytes;
  std::int64_t cached = 0;
  // Each step down the index is a few cache misses under random access: the next block is
  // looked up only when the range goes past this one.
  for (Located at = at_or_after(file, offset); at.id != kNoBlock && at.offset < end;) {
    cached += std::min(end, at.end) - std::max(offset, at.offset);
    if (at.end >= end) break;
    at = at_or_after(file, at.end);
  }
  return cached;
}

std::size_t FileRanges::check(FileId file, std::size_t most) const {
  const Tree& t = tree(file);
  PC_ASSERT_MSG(tracked(file) || t.root == kNoNode, fmt::format("file {}: offsets indexed for a file not held by range", file));
  if (t.root == kNoNode) return 0;
  std::size_t seen = 0;
  std::vector<NodeId> leaves;
  const std::size_t entries =
      check_node(t.root, t.height - 1, std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max(), most, seen, leaves);
  // The leaves' links follow the tree's order, and the spans they list are disjoint.
  std::int64_t end = std::numeric_limits<std::int64_t>::min();
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    for (int e = 0; e < nodes_[leaves[i]].count; ++e) {
      const Node& leaf = nodes_[leaves[i]];
      PC_ASSERT_MSG(leaf.keys[e] >= end && leaf.ends[e] > leaf.keys[e], fmt::format("file {}: block {} overlaps the one before, or is empty", file, leaf.ids[e]));
      end = leaf.ends[e];
    }
    PC_ASSERT_MSG(nodes_[leaves[i]].prev == (i == 0 ? kNoNode : leaves[i - 1]), fmt::format("file {}: leaf links out of order", file));
    PC_ASSERT_MSG(nodes_[leaves[i]].next == (i + 1 == leaves.size() ? kNoNode : leaves[i + 1]), fmt::format("file {}: leaf links out of order", file));
  }
  return entries;
}

std::size_t FileRanges::check_node(NodeId n, int level, std::int64_t low, std::int64_t high, std::size_t most, std::size_t& seen,
                                   std::vector<NodeId>& leaves) const {
  const Node& node = nodes_[n];
  PC_ASSERT_MSG(node.count > 0 && node.count <= kFan, fmt::format("offset index node {} holds {} entries", n, node.count));
  PC_ASSERT_MSG(node.leaf == (level == 0), "offset index out of balance");
  if (node.leaf) {
    leaves.push_back(n);
    for (int i = 0; i < node.count; ++i) {
      PC_ASSERT_MSG(++seen <= most, "a file's offset index holds more entries than there are blocks (a cycle?)");
      PC_ASSERT_MSG(node.keys[i] >= low && node.keys[i] < high && (i == 0 || node.keys[i - 1] < node.keys[i]),
                    fmt::format("offset index: offset {} out of order", node.keys[i]));
      PC_ASSERT_MSG(spans_[node.ids[i]].offset == node.keys[i],
                    fmt::format("block {}: offset {} indexed at {}", node.ids[i], spans_[node.ids[i]].offset, node.keys[i]));
      PC_ASSERT_MSG(spans_[node.ids[i]].end == node.ends[i],
                    fmt::format("block {}: end {} indexed as {}", node.ids[i], spans_[node.ids[i]].end, node.ends[i]));
    }
    return node.count;
  }
  std::size_t entries = 0;
  for (int i = 0; i < node.count; ++i) {
    const std::int64_t child_low = i == 0 ? low : node.keys[i];
    const std::int64_t child_high = i + 1 < node.count ? node.keys[i + 1] : high;
    PC_ASSERT_MSG(child_low >= low && child_high <= high && child_low < child_high, "offset index: inner keys out of order");
    entries += check_node(node.ids[i], level - 1, child_low, child_high, most, seen, leaves);
  }
  return entries;
}

}  // namespace pagecache::cache
