#include "formats/wfformat/links.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iterator>
#include <limits>

namespace pagecache::formats::wfformat {

std::pair<std::size_t, bool> NameIndex::insert(std::string_view name) {
  const auto [it, added] = index_.try_emplace(std::string(name), index_.size());
  return {it->second, added};
}

std::optional<std::size_t> NameIndex::find(std::string_view name) const {
  const auto it = index_.find(std::string(name));
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

std::vector<std::size_t> ReferenceReader::read(const JsonObject& object, std::string_view key) {
  ++list_;
  std::vector<std::size_t> out;
  for (std::string_view name : object.strings(key, fmt::format("a {} id", what_))) {
    const std::optional<std::size_t> index = names_->find(name);
    if (!index) object.fail(key, fmt::format("unknown {} {}", what_, quote_name(name)));
    if (mark_[*index] == list_) continue;
    mark_[*index] = list_;
    out.push_back(*index);
  }
  return out;
}

void check_count(const JsonObject& object, std::string_view key, std::size_t count, std::int64_t limit, std::string_view what) {
  if (limit < 0 || count > static_cast<std::uint64_t>(limit)) {
    object.fail(key, fmt::format("{} {}, more than the limit of {}", count, what, std::max<std::int64_t>(limit, 0)));
  }
}

void Warnings::add(std::string line) {
  if (workflow_->warnings.size() < kMaxWorkflowWarnings) workflow_->warnings.push_back(std::move(line));
  else ++left_out_;
}

void Warnings::finish() {
  if (left_out_ == 0) return;
  workflow_->warnings.back() = fmt::format("{}: {} more warnings, not shown", workflow_->file, left_out_ + 1);
}

std::vector<std::size_t> read_parents(const JsonObject& task, std::size_t self, ReferenceReader& tasks) {
  std::vector<std::size_t> parents = tasks.read(task, "parents");
  if (std::find(parents.begin(), parents.end(), self) != parents.end()) task.fail("parents", "lists the task itself");
  return parents;
}

void warn_about_children(const std::vector<WfTask>& tasks, const std::vector<ListedChildren>& listed, Warnings& warnings) {
  std::vector<std::vector<std::size_t>> implied(tasks.size());  // the children the parents make
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    for (std::size_t p : tasks[t].parents) implied[p].push_back(t);
  }
  for (std::size_t self = 0; self < listed.size() && self < tasks.size(); ++self) {
    const ListedChildren& l = listed[self];
    if (l.key.empty()) continue;
    std::vector<std::size_t> said = l.children;
    std::sort(said.begin(), said.end());
    const std::vector<std::size_t>& made = implied[self];  // increasing: built in task order
    if (said == made) continue;
    std::vector<std::size_t> extra;
    std::vector<std::size_t> missing;
    std::set_difference(said.begin(), said.end(), made.begin(), made.end(), std::back_inserter(extra));
    std::set_difference(made.begin(), made.end(), said.begin(), said.end(), std::back_inserter(missing));
    std::vector<std::string> parts;
    const auto itself = std::find(extra.begin(), extra.end(), self);
    if (itself != extra.end()) {
      parts.push_back("lists the task itself");
      extra.erase(itself);
    }
    const auto some = [&](const std::vector<std::size_t>& v) {
      return v.size() == 1 ? quote_name(tasks[v[0]].id) : fmt::format("{} and {} more", quote_name(tasks[v[0]].id), v.size() - 1);
    };
    if (!extra.empty()) parts.push_back(fmt::format("lists {}, whose parents do not name this task", some(extra)));
    if (!missing.empty()) parts.push_back(fmt::format("leaves out {}, whose parents name this task", some(missing)));
    warnings.add(l.task.message(l.key, fmt::format("{}; ignored: the parents alone make the dependencies", fmt::join(parts, ", and "))));
  }
}

// The speed as written, refused nowhere: only compute = "speed" uses it (and checks it).
WfMachineSpeed machine_speed(const JsonObject& machine, std::string_view speed_key) {
  WfMachineSpeed speed;
  speed.place = machine.message(fmt::format("cpu.{}", speed_key), "");
  speed.place.resize(speed.place.size() - 2);  // the message's ": " before its (empty) text
  const nlohmann::json* cpu = machine.find("cpu");
  if (cpu == nullptr || !cpu->is_object() || !cpu->contains(speed_key)) return speed;
  const nlohmann::json& value = (*cpu)[std::string(speed_key)];
  speed.mhz = value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
  return speed;
}

NameIndex read_machine_list(const JsonObject& holder, std::string_view key, std::string_view speed_key, WfWorkflow& out) {
  NameIndex known;
  const nlohmann::json::array_t* machines = holder.optional_array(key);
  if (machines == nullptr) return known;
  for (std::size_t i = 0; i < machines->size(); ++i) {
    JsonObject machine = holder.item(key, *machines, i);
    std::string name = machine.required_string("nodeName", "every machine needs its nodeName");
    machine.describe("machine " + quote_name(name));
    const auto [first, added] = known.insert(name);
    if (!added) machine.fail("nodeName", fmt::format("a second machine {}: the first is {}[{}]", quote_name(name), key, first));
    out.machines.push_back(std::move(name));
    out.machine_speeds.push_back(machine_speed(machine, speed_key));
  }
  return known;
}

std::vector<std::string> read_task_machines(const JsonObject& task, std::initializer_list<std::string_view> keys, const NameIndex& known,
                                            std::string_view known_path) {
  const std::string_view key = task.one_of(keys);
  std::vector<std::string> out;
  if (key.empty()) return out;
  if (key == "machine") {
    out.push_back(task.required_string(key, ""));
  } else {
    for (std::string_view name : task.strings(key, "a machine's nodeName")) out.emplace_back(name);
  }
  if (known.size() == 0) return out;
  for (const std::string& name : out) {
    if (!known.find(name)) task.fail(key, fmt::format("unknown machine {} (not in {})", quote_name(name), known_path));
  }
  return out;
}

}  // namespace pagecache::formats::wfformat
