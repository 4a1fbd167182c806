#include "workload/deleted_files.hpp"

#include <pagecache/error.hpp>

#include <pagecache/units.hpp>

#include <fmt/format.h>

namespace pagecache::workload {

void DeletedFiles::note_access(std::uint32_t file, bool reading, std::string_view owner, std::string_view task, bool in_application) {
  const auto it = deleted_.find(file);
  if (it == deleted_.end()) return;
  if (!reading) {
    deleted_.erase(it);
    return;
  }
  const Deletion& d = it->second;
  const auto of = [](bool application, std::string_view name) { return fmt::format("{} '{}'", application ? "application" : "workflow", name); };
  const PlacedFile& placed = platform_.files()[file];
  throw SimulationError(fmt::format("task '{}' of {} reads file '{}', which task '{}' of {} deleted at t = {} s", task, of(in_application, owner),
                                    placed.host->file_name(placed.ref), d.task, of(d.in_application, d.owner), units::format_instant(d.time)));
}

void DeletedFiles::note_deleted(std::uint32_t file, std::string_view owner, std::string_view task, bool in_application, double time) {
  deleted_.insert_or_assign(file, Deletion{std::string(task), std::string(owner), in_application, time});
}

}  // namespace pagecache::workload
