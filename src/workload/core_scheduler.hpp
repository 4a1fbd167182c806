#pragma once
// CoreScheduler: the cores of a workflow's hosts, handed to its tasks. A task asks for some
// cores on its own host, or on any of the workflow's shared hosts, and gets the first of them
// (in the workflow's order) with enough free at once; otherwise it waits. When a host gives
// cores back, the waiting tasks that fit there are served in the order they asked (a task
// that needs many cores does not hold back later ones that fit).
//
// The first shared host with enough free cores is found in a tree of the hosts' free cores
// (O(log hosts)): a cluster of 10^5 hosts running 10^6 tasks must not scan every host per task.

#include <pagecache/event.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>

#include <algorithm>
#include <cstddef>
#include <list>
#include <vector>

namespace pagecache::workload {

class CoreScheduler {
 public:
  static constexpr std::size_t kShared = static_cast<std::size_t>(-1);

  /// `cores[h]`: the cores of host h; `shared`: the hosts a task without its own may run on,
  /// in order of preference.
  CoreScheduler(Simulator& sim, std::vector<int> cores, const std::vector<std::size_t>& shared)
      : sim_(&sim), free_(std::move(cores)), position_(free_.size(), kShared), shared_(shared) {
    for (std::size_t i = 0; i < shared_.size(); ++i) {
      if (position_[shared_[i]] == kShared) position_[shared_[i]] = i;
    }
    leaves_ = 1;
    while (leaves_ < shared_.size()) leaves_ *= 2;
    tree_.assign(2 * leaves_, -1);
    for (std::size_t i = 0; i < shared_.size(); ++i) tree_[leaves_ + i] = free_[shared_[i]];
    for (std::size_t n = leaves_ - 1; n >= 1; --n) tree_[n] = std::max(tree_[2 * n], tree_[2 * n + 1]);
  }

  /// Waits until `own` (a host index), or with kShared one of the shared hosts, has `cores`
  /// free, takes them and returns that host.
  Task<std::size_t> acquire(std::size_t own, int cores) {
    if (const std::size_t host = fitting(own, cores); host != kShared) {
      take(host, cores);
      co_return host;
    }
    Event ready(*sim_);
    Waiter waiter{own, cores, &ready, kShared};
    waiters_.push_back(&waiter);
    co_await ready.wait();  // a release handed the cores over
    co_return waiter.granted;
  }

  void release(std::size_t host, int cores) {
    add(host, cores);
    // Only `host` has more room than when the waiters found none.
    for (auto it = waiters_.begin(); it != waiters_.end() && free_[host] > 0;) {
      Waiter& w = **it;
      const bool accepts = w.own == kShared ? position_[host] != kShared : w.own == host;
      if (!accepts || free_[host] < w.cores || (w.own == kShared && fitting(kShared, w.cores) != host)) {
        ++it;
        continue;
      }
      take(host, w.cores);
      w.granted = host;
      w.ready->trigger();
      it = waiters_.erase(it);
    }
  }

 private:
  struct Waiter {
    std::size_t own;
    int cores;
    Event* ready;
    std::size_t granted;
  };

  // The host a request would get now, or kShared if none has room.
  std::size_t fitting(std::size_t own, int cores) const {
    if (own != kShared) return free_[own] >= cores ? own : kShared;
    if (tree_.size() < 2 || tree_[1] < cores) return kShared;
    std::size_t n = 1;
    while (n < leaves_) n = tree_[2 * n] >= cores ? 2 * n : 2 * n + 1;  // the leftmost leaf with room
    return shared_[n - leaves_];
  }
  void take(std::size_t host, int cores) { add(host, -cores); }
  void add(std::size_t host, int cores) {
    free_[host] += cores;
    if (position_[host] == kShared) return;
    std::size_t n = leaves_ + position_[host];
    tree_[n] = free_[host];
    for (n /= 2; n >= 1; n /= 2) tree_[n] = std::max(tree_[2 * n], tree_[2 * n + 1]);
  }

  Simulator* sim_;
  std::vector<int> free_;
  std::vector<std::size_t> position_;  // per host: its place among the shared hosts, or kShared
  std::vector<std::size_t> shared_;
  std::size_t leaves_ = 1;
  std::vector<int> tree_;       // max free cores over the shared hosts, a leaf per host (-1: none)
  std::list<Waiter*> waiters_;  // in the order they asked
};

}  // namespace pagecache::workload
