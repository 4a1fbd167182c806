#include "cache/lru_list.hpp"

#include "cache/sub_list.hpp"
#include "engine/check.hpp"

#include <fmt/format.h>

namespace pagecache::cache {

LruList::~LruList() {
  for (auto& list : by_state_) list.clear();
  blocks_.clear();
}

void LruList::link_state(Block& block) {
  // With no other block of its state before it (the one block taken for writeback) it is
  // placed at once.
  const BlockState state = block.state;
  link_in_order(blocks_, by_state_[index(state)], block, [state](const Block& b) { return b.state == state; });
}

void LruList::push_back(Block& block) {
  PC_ASSERT(block.size > 0);
  block.list = kind_;
  block.order = ++last_order_;
  blocks_.push_back(block);
  by_state_[index(block.state)].push_back(block);
  bytes_ += block.size;
  state_bytes_[index(block.state)] += block.size;
}

void LruList::insert_after(Block& position, Block& block) {
  PC_ASSERT(block.size > 0 && position.list == kind_);
  block.list = kind_;
  block.order = position.order;
  blocks_.insert(std::next(blocks_.iterator_to(position)), block);
  if (block.state == position.state) {
    StateOrder& list = by_state_[index(block.state)];
    list.insert(std::next(list.iterator_to(position)), block);
  } else {
    link_state(block);
  }
  bytes_ += block.size;
  state_bytes_[index(block.state)] += block.size;
}

void LruList::erase(Block& block) {
  PC_ASSERT(block.list == kind_ && block.lru_hook.is_linked());
  blocks_.erase(blocks_.iterator_to(block));
  StateOrder& list = by_state_[index(block.state)];
  list.erase(list.iterator_to(block));
  bytes_ -= block.size;
  state_bytes_[index(block.state)] -= block.size;
}

void LruList::set_state(Block& block, BlockState state) {
  if (block.state == state) return;
  StateOrder& from = by_state_[index(block.state)];
  from.erase(from.iterator_to(block));
  state_bytes_[index(block.state)] -= block.size;
  block.state = state;
  state_bytes_[index(state)] += block.size;
  link_state(block);
}

void LruList::resize(Block& block, std::int64_t new_size) {
  PC_ASSERT(new_size > 0);
  bytes_ += new_size - block.size;
  state_bytes_[index(block.state)] += new_size - block.size;
  block.size = new_size;
}

Block* LruList::next(Block& block) noexcept {
  auto it = std::next(blocks_.iterator_to(block));
  return it == blocks_.end() ? nullptr : &*it;
}

Block* LruList::front(BlockState state) noexcept {
  StateOrder& list = by_state_[index(state)];
  return list.empty() ? nullptr : &list.front();
}

Block* LruList::next(Block& block, BlockState state) noexcept {
  StateOrder& list = by_state_[index(state)];
  auto it = std::next(list.iterator_to(block));
  return it == list.end() ? nullptr : &*it;
}

void LruList::check() const {
  std::int64_t total = 0;
  std::array<std::int64_t, 3> per_state{};
  std::array<std::size_t, 3> counts{};
  const Block* previous = nullptr;
  for (const Block& b : blocks_) {
    PC_ASSERT(b.size > 0 && b.list == kind_);
    // Order keys never decrease along the list; equal keys are pieces of one file's block.
    PC_ASSERT_MSG(b.order > 0 && b.order <= last_order_, "order key never given");
    if (previous != nullptr) {
      PC_ASSERT_MSG(b.order >= previous->order, "order keys out of LRU order");
      PC_ASSERT_MSG(b.order != previous->order || b.file == previous->file, "two files' blocks share an order key");
    }
    previous = &b;
    total += b.size;
    per_state[index(b.state)] += b.size;
    ++counts[index(b.state)];
  }
  PC_ASSERT_MSG(total == bytes_, fmt::format("list bytes {} != block sum {}", bytes_, total));
  for (std::size_t s = 0; s < 3; ++s) {
    PC_ASSERT(per_state[s] == state_bytes_[s]);
    PC_ASSERT(counts[s] == by_state_[s].size());
    // Each sub-list follows the LRU order of the main list.
    auto sub = by_state_[s].begin();
    for (const Block& b : blocks_) {
      if (index(b.state) != s) continue;
      PC_ASSERT_MSG(&*sub == &b, "state sub-list out of LRU order");
      ++sub;
    }
  }
}

}  // namespace pagecache::cache
