#pragma once
// link_in_order: puts a block into a sub-list kept in the relative order of a list that holds
// it (an LRU list's state sub-lists, a file's clean blocks within its file list).

#include <iterator>

namespace pagecache::cache {

/// Links `block`, an element of `list`, into `sub` (whose members satisfy `member` and are all
/// in `list`, in its order): right after the nearest member before it in `list`, or right
/// before the nearest one after it. Both ways are walked in turn, so the cost is the distance
/// to the nearer of the two (usually a neighbour), not to the list's end; a block with no
/// member before it, or at the end of `list`, is placed at once.
template <class List, class SubList, class Element, class IsMember>
void link_in_order(List& list, SubList& sub, Element& block, IsMember member) {
  if (sub.empty() || &list.back() == &block) {
    sub.push_back(block);
    return;
  }
  auto back = list.iterator_to(block);
  auto ahead = std::next(back);
  for (;;) {
    if (back == list.begin()) {
      sub.push_front(block);  // no member before it: it goes first
      return;
    }
    --back;
    if (member(*back)) {
      sub.insert(std::next(sub.iterator_to(*back)), block);
      return;
    }
    if (ahead == list.end()) {
      sub.push_back(block);  // no member after it: it goes last
      return;
    }
    if (member(*ahead)) {
      sub.insert(sub.iterator_to(*ahead), block);
      return;
    }
    ++ahead;
  }
}

}  // namespace pagecache::cache
