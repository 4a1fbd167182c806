#include "sweep.hpp"

#include "sweep/executor.hpp"
#include "sweep/merge.hpp"
#include "sweep/sweep.hpp"

#include <pagecache/run.hpp>

#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace py = pybind11;

namespace pcsim_python {

namespace {

// Thrown from a run's progress callback, or between the plan's checks, once Ctrl-C is seen: it
// passes execute_run's catches.
struct Stopped {};

// `work` on `threads` threads while the calling thread, without the GIL, waits for them and
// looks for Ctrl-C every tenth of a second; on one, `stop` turns true (the work is to notice
// soon) and KeyboardInterrupt is raised once every thread is back. Otherwise the first
// exception a thread threw, other than Stopped, is rethrown; it stops the others too.
void run_watched(unsigned threads, std::atomic<bool>& stop, const std::function<void()>& work) {
  std::mutex lock;
  std::condition_variable finished;
  unsigned running = threads;
  std::exception_ptr broken;
  const auto worker = [&] {
    try {
      work();
    } catch (const Stopped&) {
    } catch (...) {
      const std::lock_guard guard(lock);
      if (!broken) broken = std::current_exception();
      stop = true;
    }
    const std::lock_guard guard(lock);
    --running;
    finished.notify_all();
  };
  std::vector<std::thread> started;
  for (unsigned j = 0; j < threads; ++j) started.emplace_back(worker);
  bool interrupted = false;
  {
    std::unique_lock held(lock);
    while (running > 0) {
      if (finished.wait_for(held, std::chrono::milliseconds(100), [&] { return running == 0; })) break;
      held.unlock();
      {
        py::gil_scoped_acquire gil;
        if (!interrupted && PyErr_CheckSignals() != 0) interrupted = true;
      }
      if (interrupted) stop = true;
      held.lock();
    }
  }
  for (std::thread& t : started) t.join();
  if (interrupted) {
    py::gil_scoped_acquire gil;
    throw py::error_already_set();  // PyErr_CheckSignals left the KeyboardInterrupt set
  }
  if (broken) std::rethrow_exception(broken);
}

// The plan's runs on `jobs` threads, each line in its run's place.
std::vector<std::string> run_all(const pagecache::sweep::Sweep& plan, unsigned jobs, std::atomic<bool>& stop) {
  std::vector<std::string> lines(plan.size());
  std::atomic<std::size_t> next{0};
  pagecache::RunOptions options;
  options.progress = [&stop](double, std::uint64_t) {
    if (stop) throw Stopped{};
  };
  const unsigned threads = std::max(1u, static_cast<unsigned>(std::min<std::size_t>(jobs, std::max<std::size_t>(1, plan.size()))));
  run_watched(threads, stop, [&] {
    for (std::size_t i = next++; i < plan.size() && !stop; i = next++) lines[i] = pagecache::sweep::execute_run(plan, plan.run(i), options).line;
  });
  return lines;
}

}  // namespace

std::string sweep_csv(const std::string& path, const std::string& text, const std::string& origin, unsigned jobs, bool force) {
  py::gil_scoped_release released;
  std::atomic<bool> stop{false};
  // Making the plan tries every axis value on the base: with a large base that takes seconds.
  std::optional<pagecache::sweep::Sweep> plan;
  const auto checkpoint = [&stop] {
    if (stop) throw Stopped{};
  };
  run_watched(1, stop, [&] {
    plan.emplace(path.empty() ? pagecache::sweep::Sweep::parse(text, origin, force, {}, checkpoint)
                              : pagecache::sweep::Sweep::load(path, force, checkpoint));
  });
  return pagecache::sweep::results_csv(*plan, run_all(*plan, jobs, stop));
}

}  // namespace pcsim_python
