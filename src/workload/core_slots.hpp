#pragma once
// CoreSlots: a counting semaphore for a host's cores. A workflow task takes a core before it
// starts and gives it back when it ends; waiters are served in arrival order.

#include <pagecache/event.hpp>
#include <pagecache/simulator.hpp>

#include <deque>
#include <memory>

namespace pagecache::workload {

class CoreSlots {
 public:
  CoreSlots(Simulator& sim, int cores) : sim_(&sim), free_(cores) {}

  Task<void> acquire() {
    if (free_ > 0 && waiters_.empty()) {
      --free_;
      co_return;
    }
    auto ready = std::make_shared<Event>(*sim_);
    waiters_.push_back(ready);
    co_await ready->wait();  // the releaser handed its core over
  }

  void release() {
    if (!waiters_.empty()) {
      waiters_.front()->trigger();
      waiters_.pop_front();
    } else {
      ++free_;
    }
  }

 private:
  Simulator* sim_;
  int free_;
  std::deque<std::shared_ptr<Event>> waiters_;
};

}  // namespace pagecache::workload
