#include "report/interrupt_cleanup.hpp"

#include "report/output_rules.hpp"

#include <atomic>
#include <array>
#include <climits>
#include <csignal>
#include <pthread.h>
#include <cstring>
#include <unistd.h>

namespace pagecache::report {

namespace {

constexpr int kSlots = 64;

// A slot is written while `state` is Free -> Filling (taken by compare-exchange), published as
// Ready; the handler reads Ready slots only. Paths are fixed arrays: the handler allocates nothing.
enum State : int { Free, Filling, Ready };
struct Slot {
  std::atomic<int> state{Free};
  RemovedOnInterrupt::Kind kind = RemovedOnInterrupt::Kind::File;
  char path[PATH_MAX + 1] = {};
};
static_assert(std::atomic<int>::is_always_lock_free);

std::array<Slot, kSlots>& slots() {
  static std::array<Slot, kSlots> all;
  return all;
}

// "folder/name" into `buffer` without allocating; false if it does not fit.
bool join(char* buffer, std::size_t size, const char* folder, const char* name) {
  const std::size_t a = std::strlen(folder), b = std::strlen(name);
  if (a + 1 + b + 1 > size) return false;
  std::memcpy(buffer, folder, a);
  buffer[a] = '/';
  std::memcpy(buffer + a + 1, name, b + 1);
  return true;
}

extern "C" void on_interrupt(int signal) {
  // Files first: a temporary file may be inside a staging folder.
  for (auto kind : {RemovedOnInterrupt::Kind::File, RemovedOnInterrupt::Kind::StagingFolder}) {
    for (Slot& slot : slots()) {
      if (slot.state.load() != Ready || slot.kind != kind) continue;
      if (kind == RemovedOnInterrupt::Kind::File) {
        ::unlink(slot.path);
        continue;
      }
      char file[PATH_MAX + 1];
      for (const char* name : kOutputNames) {
        if (join(file, sizeof file, slot.path, name)) ::unlink(file);
      }
      ::rmdir(slot.path);
    }
  }
  ::_exit(128 + signal);
}

}  // namespace

void install_interrupt_cleanup() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, s);  // one handler at a time
    for (int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &action, nullptr);
    return true;
  }();
  (void)installed;
}

SignalsHeld::SignalsHeld() {
  sigset_t held;
  sigemptyset(&held);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, s);
  ::pthread_sigmask(SIG_BLOCK, &held, &previous_);
}

SignalsHeld::~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

RemovedOnInterrupt::RemovedOnInterrupt(const std::string& path, Kind kind) {
  if (path.size() > PATH_MAX) return;
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = slots()[static_cast<std::size_t>(i)];
    int expected = Free;
    if (!slot.state.compare_exchange_strong(expected, Filling)) continue;
    slot.kind = kind;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(Ready);
    slot_ = i;
    return;
  }
}

RemovedOnInterrupt::~RemovedOnInterrupt() {
  if (slot_ >= 0) slots()[static_cast<std::size_t>(slot_)].state.store(Free);
}

}  // namespace pagecache::report
