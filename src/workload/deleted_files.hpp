#pragma once
// DeletedFiles: the files a task deleted and no task has written since. A deleted file is gone
// until a task writes it again: reading it is an error, named with the task that deleted it
// (the loader refuses the reads whose order the scenario fixes; here are those the run's order
// decides).

#include "workload/platform.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>

namespace pagecache::workload {

class DeletedFiles {
 public:
  /// `platform` names the files (its Platform::files() indices are the files here).
  explicit DeletedFiles(const Platform& platform) : platform_(platform) {}

  /// Cheap: only while it is false need an access be noted.
  bool empty() const noexcept { return deleted_.empty(); }

  /// Task `task` of application (or workflow) `owner` reads or writes `file`: a write makes it
  /// exist again; a read of a deleted file throws SimulationError.
  void note_access(std::uint32_t file, bool reading, std::string_view owner, std::string_view task, bool in_application);
  /// Task `task` of `owner` deleted `file` at `time`.
  void note_deleted(std::uint32_t file, std::string_view owner, std::string_view task, bool in_application, double time);

 private:
  struct Deletion {
    std::string task;
    std::string owner;  // its application or workflow
    bool in_application;
    double time;
  };

  const Platform& platform_;
  std::unordered_map<std::uint32_t, Deletion> deleted_;  // by index in Platform::files()
};

}  // namespace pagecache::workload
