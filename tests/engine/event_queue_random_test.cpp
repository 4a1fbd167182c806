// Randomised check of EventQueue against a sorted set of (time, sequence) keys. The queue
// merges three sources (the ring of wake-ups at now, runs of events made in time order, the
// heap); random pushes at a few distinct delays (so that runs form, fill up and grow), wake-ups
// at now, cancellations and reschedulings of pending events anywhere in a run or the heap, and
// pops must give exactly the reference's order, with the sizes agreeing after every step.
#include "engine/event_queue.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <iterator>
#include <random>
#include <set>
#include <tuple>
#include <vector>

using namespace pagecache::detail;

namespace {

struct Key {
  double time;
  std::uint64_t sequence;
  int id;
  bool operator<(const Key& other) const { return std::tie(time, sequence) < std::tie(other.time, other.sequence); }
};

void ignore(void*) {}

}  // namespace

TEST_CASE("the event queue pops in (time, scheduling order) whatever its mix of sources", "[simulator][random]") {
  const unsigned seed = GENERATE(1u, 2u, 3u, 4u);
  std::mt19937_64 rng(seed);
  EventQueue queue;
  std::set<Key> reference;
  std::vector<QueuedEvent*> node_of;   // by id; nullptr once popped or cancelled
  std::vector<Key> key_of;             // by id
  std::vector<int> ids;                // storage for the contexts
  std::vector<int> cancellable;        // ids that may be pending in the run or the heap
  std::uint64_t sequence = 0;
  double now = 0.0;
  const double delays[] = {0.0, 0.25, 1.0, 1.0, 1.0, 2.5, 7.0, 60.0};
  std::uniform_real_distribution<double> jitter(0.0, 3.0);
  ids.reserve(200000);

  auto new_id = [&] {
    ids.push_back(static_cast<int>(ids.size()));
    node_of.push_back(nullptr);
    key_of.push_back({});
    return ids.back();
  };

  for (int step = 0; step < 60000; ++step) {
    const unsigned what = static_cast<unsigned>(rng() % 100);
    if (what < 40) {
      const int id = new_id();
      const double delay = (rng() % 4 == 0) ? jitter(rng) : delays[rng() % std::size(delays)];
      node_of[id] = queue.push(now + delay, &ignore, &ids[id]);
      key_of[id] = {now + delay, sequence++, id};
      reference.insert(key_of[id]);
      cancellable.push_back(id);
    } else if (what < 55) {
      const int id = new_id();
      queue.push_now(now, &ignore, &ids[id]);
      reference.insert({now, sequence++, id});
    } else if (what < 65 && !cancellable.empty()) {
      const std::size_t at = rng() % cancellable.size();
      const int id = cancellable[at];
      if (node_of[id] != nullptr) {
        queue.erase(node_of[id]);
        reference.erase(key_of[id]);
        node_of[id] = nullptr;
      }
      cancellable[at] = cancellable.back();
      cancellable.pop_back();
    } else if (what < 72 && !cancellable.empty()) {
      const int id = cancellable[rng() % cancellable.size()];
      if (node_of[id] != nullptr) {
        const double time = now + delays[rng() % std::size(delays)];
        queue.update(node_of[id], time);
        reference.erase(key_of[id]);
        key_of[id] = {time, sequence++, id};
        reference.insert(key_of[id]);
      }
    } else if (!reference.empty()) {
      REQUIRE(queue.top_time() == reference.begin()->time);
      const EventQueue::Fired fired = queue.pop();
      const Key expected = *reference.begin();
      reference.erase(reference.begin());
      REQUIRE(fired.time == expected.time);
      REQUIRE(*static_cast<int*>(fired.context) == expected.id);
      node_of[expected.id] = nullptr;
      now = fired.time;
    }
    REQUIRE(queue.size() == reference.size());
    REQUIRE(queue.empty() == reference.empty());
  }
  while (!reference.empty()) {
    const EventQueue::Fired fired = queue.pop();
    REQUIRE(*static_cast<int*>(fired.context) == reference.begin()->id);
    reference.erase(reference.begin());
  }
  REQUIRE(queue.empty());
}
