#pragma once
// What both workflow formats share: names resolved to indices (task ids, file ids, machines),
// lists of references without repeats, the bounds on counts, the warnings, the check of
// `children` against the parents, and the machines.

#include "formats/common/json_object.hpp"
#include "formats/wfformat/workflow_json.hpp"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace pagecache::formats::wfformat {

/// Names to indices, in the order they were first added.
class NameIndex {
 public:
  /// Adds `name` as index size() if new; the index it has, and whether it was new.
  std::pair<std::size_t, bool> insert(std::string_view name);
  std::optional<std::size_t> find(std::string_view name) const;
  std::size_t size() const noexcept { return index_.size(); }

 private:
  std::unordered_map<std::string, std::size_t> index_;
};

/// Resolves arrays of names to indices into a NameIndex, each index once per array, in the
/// order listed; in O(1) per item, so that a hostile list of 10^6 repeats costs 10^6 steps.
class ReferenceReader {
 public:
  /// `what` names an item in messages: "task", "file", "machine".
  ReferenceReader(const NameIndex& names, std::string_view what) : names_(&names), what_(what), mark_(names.size(), 0) {}
  /// The indices the strings at `key` of `object` name; an unknown name is a ConfigError.
  std::vector<std::size_t> read(const JsonObject& object, std::string_view key);

 private:
  const NameIndex* names_;
  std::string what_;
  std::vector<std::size_t> mark_;  // per name: the list it was last seen in, from 1
  std::size_t list_ = 0;
};

/// Refuses `count` items at `key` of `object` beyond `limit`, naming both.
void check_count(const JsonObject& object, std::string_view key, std::size_t count, std::int64_t limit, std::string_view what);

/// The workflow's warnings, at most kMaxWorkflowWarnings of them.
class Warnings {
 public:
  explicit Warnings(WfWorkflow& workflow) : workflow_(&workflow) {}
  void add(std::string line);
  /// Adds, if some were left out, a last line saying how many.
  void finish();

 private:
  WfWorkflow* workflow_;
  std::size_t left_out_ = 0;
};

/// The children one task lists (`children`, or the old format's `childrens`), kept until the
/// parents of every task are known.
struct ListedChildren {
  JsonObject task;
  std::string key;  ///< the key they were listed under; empty if the task lists none
  std::vector<std::size_t> children;
};

/// Warns about each task whose listed children (`listed`, one per task, in task order) disagree
/// with the parents of all tasks. The parents alone make the dependencies (as in WRENCH, whose
/// old-format reader never reads `childrens`): WfFormat makes `children` redundant, and the
/// real inputs get it wrong: nighres_workflow.json's extract_brain_region lists itself, and
/// not the task whose parent it is. A child naming no task at all is refused when read, as a
/// typo would be.
void warn_about_children(const std::vector<WfTask>& tasks, const std::vector<ListedChildren>& listed, Warnings& warnings);

/// Reads the parents of task `self` (key "parents"); a task listing itself is refused.
std::vector<std::size_t> read_parents(const JsonObject& task, std::size_t self, ReferenceReader& tasks);

/// The machines listed at `key` of `holder` (objects with a `nodeName`, each once), appended
/// to `out.machines`, with their cpu.`speed_key` (whatever it holds) to `out.machine_speeds`;
/// their index.
NameIndex read_machine_list(const JsonObject& holder, std::string_view key, std::string_view speed_key, WfWorkflow& out);

/// The machines a task ran on, at whichever of `keys` it has (an array of names; the old
/// `machine`, a single name). Each must be in `known`, unless the workflow lists none.
std::vector<std::string> read_task_machines(const JsonObject& task, std::initializer_list<std::string_view> keys, const NameIndex& known,
                                            std::string_view known_path);

/// The cores a task may ask for: beyond this a number is a typo or hostile.
inline constexpr std::int64_t kMaxCores = 1'000'000;

}  // namespace pagecache::formats::wfformat
