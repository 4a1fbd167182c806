// IndexedHeap against a sorted reference, through random pushes, erasures and pops, ordered and
// unordered, with every entry's recorded index checked after each change.

#include "engine/indexed_heap.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

namespace pagecache::detail {
namespace {

struct Item {
  double key = 0.0;
  std::uint64_t sequence = 0;
  std::uint32_t index = 0;  // where the heap says it is
};

struct Entry {
  double key;
  std::uint64_t sequence;
  Item* item;
};

struct Before {
  bool operator()(const Entry& a, const Entry& b) const noexcept {
    return a.key < b.key || (a.key == b.key && a.sequence < b.sequence);
  }
};

struct Place {
  void operator()(const Entry& e, std::uint32_t index) const noexcept { e.item->index = index; }
};

using Heap = IndexedHeap<Entry, Before, Place>;

void check_indices(const Heap& heap) {
  for (std::uint32_t i = 0; i < heap.size(); ++i) REQUIRE(heap.at(i).item->index == i);
}

TEST_CASE("IndexedHeap keeps order and indices, ordered and unordered", "[engine][heap][random]") {
  std::mt19937_64 rng(7);
  std::vector<Item> items(4000);
  std::set<std::pair<double, std::uint64_t>> reference;
  std::vector<Item*> inside;
  Heap heap;
  bool ordered = false;
  std::uint64_t next = 0;
  for (int step = 0; step < 20000; ++step) {
    const auto action = std::uniform_int_distribution<int>(0, 9)(rng);
    if (action < 5 && next < items.size()) {
      Item& item = items[next];
      item.key = static_cast<double>(std::uniform_int_distribution<int>(0, 50)(rng));  // many ties
      item.sequence = next++;
      reference.emplace(item.key, item.sequence);
      inside.push_back(&item);
      if (ordered) heap.push({item.key, item.sequence, &item});
      else heap.push_unordered({item.key, item.sequence, &item});
    } else if (action < 8 && !inside.empty()) {
      const std::size_t pick = std::uniform_int_distribution<std::size_t>(0, inside.size() - 1)(rng);
      Item* item = inside[pick];
      inside[pick] = inside.back();
      inside.pop_back();
      reference.erase({item->key, item->sequence});
      if (ordered) heap.erase(item->index);
      else heap.erase_unordered(item->index);
    } else if (!heap.empty()) {
      if (!ordered) {
        heap.make_ordered();
        ordered = true;
      }
      REQUIRE(heap.ordered());
      const Entry top = heap.top();
      REQUIRE(std::make_pair(top.key, top.sequence) == *reference.begin());
      if (action == 9) {
        reference.erase(reference.begin());
        inside.erase(std::find(inside.begin(), inside.end(), top.item));
        heap.pop();
      }
    }
    if (heap.empty()) ordered = false;
    if (std::uniform_int_distribution<int>(0, 99)(rng) == 0 && ordered) {
      // Back to unordered use: any array order is a valid unordered state.
      ordered = false;
    }
    REQUIRE(heap.size() == reference.size());
    if (ordered) REQUIRE(heap.ordered());
    check_indices(heap);
  }
}

}  // namespace
}  // namespace pagecache::detail
