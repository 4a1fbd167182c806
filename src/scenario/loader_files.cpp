// The files of a scenario: its [[files]] and [[file_sets]] tables, and the checks of every file
// (those of the pipelines and workflow included) against the disks that store them.

#include "scenario/loader_sections.hpp"

#include "scenario/limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

namespace pagecache::scenario {

namespace {

// Where a file, or each file of a set (`what`), is stored: its host and disk keys, the disk
// defaulting to the host's first. Returns the host.
const HostConfig& read_placement(TomlReader& f, const Scenario& s, const std::string& what, std::string& host, std::string& disk) {
  host = f.name("host", s.hosts.front().name);
  disk = f.name("disk", "");
  const auto h = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == host; });
  if (h == s.hosts.end()) f.fail("host", fmt::format("no host named '{}'", host));
  if (disk.empty()) {
    // A platform file's host may have none (a SimGrid cluster's).
    if (h->disks.empty()) f.fail("host", fmt::format("host '{}' has no disk to store {}", host, what));
    disk = h->disks.front().name;
  }
  return *h;
}

}  // namespace

void read_files(TomlReader& r, const std::string& file, Scenario& s, Origins& origins) {
  const auto files = r.tables("files");
  for (std::size_t i = 0; i < files.size(); ++i) {
    TomlReader f(*files[i], r.child_path("files", i), file);
    origins.files.push_back({files[i], f.path(), &file});
    FileSpec spec;
    spec.name = f.required_name("name");
    spec.size = f.required_size("size");
    read_placement(f, s, fmt::format("file '{}'", spec.name), spec.host, spec.disk);
    spec.cached = f.optional_bool("cached").value_or(false);
    f.finish();
    s.files.push_back(std::move(spec));
  }
}

void read_file_sets(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins) {
  const auto sets = r.tables("file_sets");
  for (std::size_t i = 0; i < sets.size(); ++i) {
    TomlReader f(*sets[i], r.child_path("file_sets", i), file);
    origins.file_sets.push_back({sets[i], f.path(), &file});
    FileSetSpec spec;
    spec.name = f.required_name("name");
    // The run's file limit (check_limits) refuses a large count before any file is made.
    spec.count = f.required_integer("count");
    if (spec.count < 1) f.fail("count", fmt::format("must be >= 1, got {}", spec.count));
    // Before any check that sums its files (check_limits counts the run's files again, all made).
    double files = static_cast<double>(s.files.size());
    for (const FileSetSpec& other : s.file_sets) files += static_cast<double>(other.count);
    if (files + static_cast<double>(spec.count) > static_cast<double>(limits.max_files)) {
      f.fail("count", fmt::format("{:.0f} files, more than the {} a run may have{}", files + static_cast<double>(spec.count), limits.max_files,
                                  limits_hint(limits)));
    }
    spec.size = f.required_size("size");
    const HostConfig* h = &read_placement(f, s, fmt::format("file set '{}'", spec.name), spec.host, spec.disk);
    spec.cached = f.optional_bool("cached").value_or(false);
    const auto d = std::find_if(h->disks.begin(), h->disks.end(), [&](const DiskSpec& x) { return x.name == spec.disk; });
    if (d == h->disks.end()) f.fail("disk", fmt::format("file set '{}': host '{}' has no disk '{}'", spec.name, h->name, spec.disk));
    if (d->capacity > 0 && spec.size > d->capacity) {
      f.fail("size", fmt::format("the files of set '{}' ({} each) do not fit on disk '{}' ({})", spec.name, units::format_size(spec.size),
                                 d->name, units::format_size(d->capacity)));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (s.file_sets[j].name == spec.name) f.fail("name", fmt::format("two file sets named '{}'", spec.name));
    }
    f.finish();
    s.file_sets.push_back(std::move(spec));
  }
}

namespace {

// The set whose member `name` would be ("SET/7": SET's eighth file), if any.
const FileSetSpec* member_of(const std::string& name, const std::vector<FileSetSpec>& sets) {
  const std::size_t slash = name.rfind('/');
  if (slash == std::string::npos || slash + 1 == name.size()) return nullptr;
  const std::string_view number = std::string_view(name).substr(slash + 1);
  if (number.size() > 18 || (number.size() > 1 && number.front() == '0')) return nullptr;
  std::int64_t n = 0;
  for (const char c : number) {
    if (c < '0' || c > '9') return nullptr;
    n = n * 10 + (c - '0');
  }
  const std::string_view prefix = std::string_view(name).substr(0, slash);
  for (const FileSetSpec& set : sets) {
    if (set.name == prefix && n < set.count) return &set;
  }
  return nullptr;
}

}  // namespace

// The references of the files: each names a disk its host has, and fits it.
std::map<std::string, const FileSpec*> check_files(const Scenario& s, const Origins& origins) {
  std::map<std::string, const FileSpec*> by_name;
  std::unordered_map<std::string_view, const HostConfig*> host_by_name;
  for (const HostConfig& h : s.hosts) host_by_name.emplace(h.name, &h);
  for (std::size_t i = 0; i < s.files.size(); ++i) {
    const FileSpec& f = s.files[i];
    if (!by_name.emplace(f.name, &f).second) origins.file(i).fail("name", fmt::format("two files named '{}'", f.name));
    if (const FileSetSpec* set = member_of(f.name, s.file_sets)) {
      origins.file(i).fail("name", fmt::format("'{}' is the name of a file of file set '{}'", f.name, set->name));
    }
    const HostConfig& h = *host_by_name.at(f.host);
    const auto d = std::find_if(h.disks.begin(), h.disks.end(), [&](const DiskSpec& x) { return x.name == f.disk; });
    if (d == h.disks.end()) origins.file(i).fail("disk", fmt::format("file '{}': host '{}' has no disk '{}'", f.name, h.name, f.disk));
    if (d->capacity > 0 && f.size > d->capacity) {
      origins.file(i).fail(i < origins.files.size() ? "size" : "file_size",
                           fmt::format("file '{}' ({}) does not fit on disk '{}' ({})", f.name, units::format_size(f.size), d->name,
                                       units::format_size(d->capacity)));
    }
  }
  // A task names a file or a set by its name alone: one name, one thing.
  for (std::size_t i = 0; i < s.file_sets.size(); ++i) {
    if (by_name.count(s.file_sets[i].name) != 0) {
      origins.file_sets[i].fail("name", fmt::format("a file is named '{}' too: a file set's name must not be a file's", s.file_sets[i].name));
    }
  }
  return by_name;
}

// What the files on each disk take at the start (those no task writes) and at the end (those no
// task deletes): both must fit its capacity. Files written and deleted meanwhile may need more.
void check_disk_space(const Scenario& s, const Origins& origins) {
  const bool any_capacity = std::any_of(s.hosts.begin(), s.hosts.end(), [](const HostConfig& h) {
    return std::any_of(h.disks.begin(), h.disks.end(), [](const DiskSpec& d) { return d.capacity > 0; });
  });
  if (!any_capacity) return;
  std::unordered_set<std::string_view> written, deleted;
  auto note = [&](const std::vector<TaskSpec>& tasks) {
    for (const TaskSpec& t : tasks) {
      written.insert(t.writes.begin(), t.writes.end());
      deleted.insert(t.deletes.begin(), t.deletes.end());
    }
  };
  for (const AppSpec& a : s.apps) note(a.tasks);
  for (const WorkflowSpec& w : s.workflows) note(w.tasks);
  // What each disk holds at the start and at the end, summed in one pass over the files.
  std::map<std::pair<std::string_view, std::string_view>, std::pair<std::int64_t, std::int64_t>> held;
  for (const FileSpec& f : s.files) {
    auto& [at_start, at_end] = held[{f.host, f.disk}];  // at most 2^60 each, summed while below 2^62
    if (written.count(f.name) == 0) at_start = std::min(at_start + f.size, units::kMaxBytes * 2);
    if (deleted.count(f.name) == 0) at_end = std::min(at_end + f.size, units::kMaxBytes * 2);
  }
  for (const FileSetSpec& set : s.file_sets) {  // never written nor deleted
    auto& [at_start, at_end] = held[{set.host, set.disk}];
    const double bytes = static_cast<double>(set.count) * static_cast<double>(set.size);
    const std::int64_t all = bytes >= static_cast<double>(units::kMaxBytes) ? units::kMaxBytes * 2 : static_cast<std::int64_t>(bytes);
    at_start = std::min(at_start + all, units::kMaxBytes * 2);
    at_end = std::min(at_end + all, units::kMaxBytes * 2);
  }
  for (std::size_t h = 0; h < s.hosts.size(); ++h) {
    for (std::size_t d = 0; d < s.hosts[h].disks.size(); ++d) {
      const DiskSpec& disk = s.hosts[h].disks[d];
      if (disk.capacity <= 0) continue;
      const auto sums = held.find({s.hosts[h].name, disk.name});
      if (sums == held.end()) continue;
      const auto [at_start, at_end] = sums->second;
      const bool start = at_start >= at_end;
      const std::int64_t needed = std::max(at_start, at_end);
      if (needed > disk.capacity) {
        origins.disks[h][d].fail(origins.disks[h][d].has("capacity") ? "capacity" : "name",
                                 fmt::format("the files on disk '{}' of host '{}' take {} {}, more than its capacity of {}", disk.name,
                                             s.hosts[h].name, units::format_size(needed),
                                             start ? "when the run starts (the files no task writes)"
                                                   : "when the run ends (the files no task deletes)",
                                             units::format_size(disk.capacity)));
      }
    }
  }
}

}  // namespace pagecache::scenario
