#pragma once
// A memory cgroup pcsim makes for one real run (`validate --here --fio --memory-max`), so that
// the run meets the limit pcsim simulates: cgroup v2 (memory.max) where this process's group
// offers the memory controller to its children, else cgroup v1 (memory.limit_in_bytes) below
// this process's memory group. Removed with the object, also when a run fails or is stopped.

#include <cstdint>
#include <filesystem>

namespace pagecache::calibrate {

class MemoryCgroup {
 public:
  /// Makes a group pcsim-fio-PID-N limited to `max_bytes`. Throws pagecache::Error naming the
  /// path and the reason if it cannot (not root, no memory controller).
  explicit MemoryCgroup(std::int64_t max_bytes);
  /// Removes it (its tasks must have ended; retried briefly while the kernel still holds it).
  ~MemoryCgroup();
  MemoryCgroup(const MemoryCgroup&) = delete;
  MemoryCgroup& operator=(const MemoryCgroup&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  /// Its cgroup.procs: a process that writes its pid there joins the group.
  std::filesystem::path procs() const { return dir_ / "cgroup.procs"; }
  bool v2() const { return v2_; }
  /// The most memory its tasks used at once (v1 memory.max_usage_in_bytes, v2 memory.peak),
  /// bytes; -1 if the kernel does not tell.
  std::int64_t peak() const;

 private:
  std::filesystem::path dir_;
  bool v2_ = false;
};

}  // namespace pagecache::calibrate
