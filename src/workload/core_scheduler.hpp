#pragma once
// CoreScheduler: the cores of a workflow's hosts, handed to its tasks. A task asks for some
// cores on any of a list of hosts (its own, or the workflow's) and gets the first of them with
// enough free at once; otherwise it waits. When cores are given back, the waiting tasks are
// served in the order they asked, each as soon as a host has room for it (a task that needs
// many cores does not hold back later ones that fit).

#include <pagecache/event.hpp>
#include <pagecache/simulator.hpp>
#include <pagecache/task.hpp>

#include <cstddef>
#include <list>
#include <span>
#include <vector>

namespace pagecache::workload {

class CoreScheduler {
 public:
  /// `cores[h]`: the cores of host h.
  CoreScheduler(Simulator& sim, std::vector<int> cores) : sim_(&sim), free_(std::move(cores)) {
    for (const int c : free_) total_free_ += c;
  }

  /// Waits until one of `hosts` (indices, in order of preference; they must outlive the wait)
  /// has `cores` free, takes them and returns that host.
  Task<std::size_t> acquire(std::span<const std::size_t> hosts, int cores) {
    if (const auto host = fitting(hosts, cores); host != kNone) {
      take(host, cores);
      co_return host;
    }
    Event ready(*sim_);
    Waiter waiter{hosts, cores, &ready, kNone};
    waiters_.push_back(&waiter);
    co_await ready.wait();  // a release handed the cores over
    co_return waiter.granted;
  }

  void release(std::size_t host, int cores) {
    free_[host] += cores;
    total_free_ += cores;
    for (auto it = waiters_.begin(); it != waiters_.end() && total_free_ > 0;) {
      Waiter& w = **it;
      const std::size_t fit = fitting(w.hosts, w.cores);
      if (fit == kNone) {
        ++it;
        continue;
      }
      take(fit, w.cores);
      w.granted = fit;
      w.ready->trigger();
      it = waiters_.erase(it);
    }
  }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct Waiter {
    std::span<const std::size_t> hosts;
    int cores;
    Event* ready;
    std::size_t granted;
  };

  std::size_t fitting(std::span<const std::size_t> hosts, int cores) const {
    for (const std::size_t h : hosts) {
      if (free_[h] >= cores) return h;
    }
    return kNone;
  }
  void take(std::size_t host, int cores) {
    free_[host] -= cores;
    total_free_ -= cores;
  }

  Simulator* sim_;
  std::vector<int> free_;
  long long total_free_ = 0;
  std::list<Waiter*> waiters_;  // in the order they asked; served out of order when they fit
};

}  // namespace pagecache::workload
