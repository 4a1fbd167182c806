#include "cache/lru_list.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

namespace pagecache::cache {

void LruList::link_state(BlockId id) {
  // With no other block of its state before it (the one block taken for writeback) it is
  // placed at once.
  const Block& block = (*pool_)[id];
  const BlockState state = block.state;
  const NodeId node = block.node;
  link_in_order(*pool_, blocks_, by_state_[sub_list(block)], id,
                [state, node](const Block& b) { return b.state == state && (state != BlockState::Clean || b.node == node); });
}

void LruList::push_back(BlockId id) {
  Block& block = (*pool_)[id];
  PC_ASSERT(block.size > 0);
  block.list = kind_;
  block.order = ++last_order_;
  blocks_.push_back(*pool_, id);
  by_state_[sub_list(block)].push_back(*pool_, id);
  bytes_ += block.size;
  state_bytes_[index(block.state)] += block.size;
}

void LruList::push_front(BlockId id) {
  Block& block = (*pool_)[id];
  PC_ASSERT(block.size > 0);
  block.list = kind_;
  block.order = --first_order_;
  blocks_.push_front(*pool_, id);
  link_state(id);
  bytes_ += block.size;
  state_bytes_[index(block.state)] += block.size;
}

void LruList::insert_after(BlockId position, BlockId id) {
  Block& block = (*pool_)[id];
  const Block& at = (*pool_)[position];
  PC_ASSERT(block.size > 0 && at.list == kind_);
  block.list = kind_;
  block.order = at.order;
  blocks_.insert_after(*pool_, position, id);
  if (sub_list(block) == sub_list(at)) by_state_[sub_list(block)].insert_after(*pool_, position, id);
  else link_state(id);
  bytes_ += block.size;
  state_bytes_[index(block.state)] += block.size;
}

void LruList::erase(BlockId id) {
  const Block& block = (*pool_)[id];
  PC_ASSERT(block.list == kind_);
  blocks_.erase(*pool_, id);
  by_state_[sub_list(block)].erase(*pool_, id);
  bytes_ -= block.size;
  state_bytes_[index(block.state)] -= block.size;
}

void LruList::set_state(BlockId id, BlockState state) {
  Block& block = (*pool_)[id];
  if (block.state == state) return;
  by_state_[sub_list(block)].erase(*pool_, id);
  state_bytes_[index(block.state)] -= block.size;
  block.state = state;
  state_bytes_[index(state)] += block.size;
  link_state(id);
}

void LruList::resize(BlockId id, std::int64_t new_size) {
  Block& block = (*pool_)[id];
  PC_ASSERT(new_size > 0);
  bytes_ += new_size - block.size;
  state_bytes_[index(block.state)] += new_size - block.size;
  block.size = new_size;
}

std::size_t LruList::blocks_in(BlockState state) const noexcept {
  std::size_t count = by_state_[index(state)].size();
  if (state == BlockState::Clean) {
    for (std::size_t s = 3; s < kSubLists; ++s) count += by_state_[s].size();
  }
  return count;
}

void LruList::check() const {
  std::int64_t total = 0;
  std::array<std::int64_t, 3> per_state{};
  std::array<std::size_t, kSubLists> counts{};
  std::size_t seen = 0;
  const Block* previous = nullptr;
  for (const Block& b : blocks()) {
    PC_ASSERT_MSG(seen < blocks_.size(), "the list holds more blocks than it counts (a cycle?)");
    PC_ASSERT(b.size > 0 && b.list == kind_);
    // Order keys never decrease along the list; equal keys are pieces of one file's block.
    PC_ASSERT_MSG(b.order >= first_order_ && b.order <= last_order_, "order key never given");
    if (previous != nullptr) {
      PC_ASSERT_MSG(b.order >= previous->order, "order keys out of LRU order");
      PC_ASSERT_MSG(b.order != previous->order || b.file == previous->file, "two files' blocks share an order key");
    }
    previous = &b;
    total += b.size;
    per_state[index(b.state)] += b.size;
    ++counts[sub_list(b)];
    ++seen;
  }
  PC_ASSERT_MSG(seen == blocks_.size(), fmt::format("list counts {} blocks, holds {}", blocks_.size(), seen));
  PC_ASSERT_MSG(total == bytes_, fmt::format("list bytes {} != block sum {}", bytes_, total));
  for (std::size_t s = 0; s < 3; ++s) PC_ASSERT(per_state[s] == state_bytes_[s]);
  for (std::size_t s = 0; s < kSubLists; ++s) {
    PC_ASSERT(counts[s] == by_state_[s].size());
    // Each sub-list follows the LRU order of the main list.
    auto sub = by_state_[s].range(*pool_).begin();
    const auto all = blocks();
    for (auto it = all.begin(); it != all.end(); ++it) {
      if (sub_list(*it) != s) continue;
      PC_ASSERT_MSG(sub.id() == it.id(), "state sub-list out of LRU order");
      ++sub;
    }
    PC_ASSERT_MSG(sub.id() == kNoBlock, "state sub-list holds a block not in the list");
  }
}

}  // namespace pagecache::cache
