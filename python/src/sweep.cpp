#include "sweep.hpp"

#include "sweep/executor.hpp"
#include "sweep/merge.hpp"
#include "sweep/plan.hpp"

#include <pagecache/run.hpp>

#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace py = pybind11;

namespace pcsim_python {

namespace {

// Thrown from a run's progress callback once Ctrl-C is seen: it passes execute_run's catches.
struct Stopped {};

// The plan's runs on `jobs` threads, each line in its run's place. The calling thread, without
// the GIL, waits for them and looks for Ctrl-C every tenth of a second.
std::vector<std::string> run_all(const pagecache::sweep::Plan& plan, unsigned jobs) {
  std::vector<std::string> lines(plan.size());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex lock;
  std::condition_variable finished;
  unsigned running = 0;
  std::exception_ptr broken;
  pagecache::RunOptions options;
  options.progress = [&stop](double, std::uint64_t) {
    if (stop) throw Stopped{};
  };
  const auto worker = [&] {
    try {
      for (std::size_t i = next++; i < plan.size() && !stop; i = next++) lines[i] = pagecache::sweep::execute_run(plan, plan.run(i), options).line;
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
  const unsigned threads_wanted = std::max(1u, static_cast<unsigned>(std::min<std::size_t>(jobs, std::max<std::size_t>(1, plan.size()))));
  std::vector<std::thread> threads;
  running = threads_wanted;
  for (unsigned j = 0; j < threads_wanted; ++j) threads.emplace_back(worker);
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
  for (std::thread& t : threads) t.join();
  if (interrupted) {
    py::gil_scoped_acquire gil;
    throw py::error_already_set();  // PyErr_CheckSignals left the KeyboardInterrupt set
  }
  if (broken) std::rethrow_exception(broken);
  return lines;
}

}  // namespace

std::string sweep_csv(const std::string& path, const std::string& text, const std::string& origin, unsigned jobs, bool force) {
  py::gil_scoped_release released;
  const pagecache::sweep::Plan plan =
      path.empty() ? pagecache::sweep::Plan::parse(text, origin, force) : pagecache::sweep::Plan::load(path, force);
  return pagecache::sweep::results_csv(plan, run_all(plan, jobs));
}

}  // namespace pcsim_python
