// Reading a scenario file: TOML text -> overrides applied -> every key read and checked ->
// shorthands expanded -> references and sizes checked.

#include <pagecache/cache_policies.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/deleted_files.hpp"
#include "scenario/limits.hpp"
#include "scenario/route_index.hpp"
#include "scenario/simgrid_import.hpp"
#include "scenario/workflow_import.hpp"
#include "scenario/origins.hpp"
#include "scenario/resolve.hpp"
#include "scenario/text_file.hpp"
#include "scenario/toml_reader.hpp"
#include "storage/readahead.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

namespace pagecache {

namespace {

// `pcsim show` of a platform alone lists at most this many routes (a cluster of N hosts has
// N (N - 1) / 2).
constexpr std::size_t kMostShownRoutes = 100'000;

using scenario::Origin;
using scenario::Origins;
using scenario::TomlReader;
using Overrides = std::vector<std::pair<std::string, std::string>>;

Profile parse_profile(const std::string& name, const std::function<void(const std::string&)>& fail) {
  if (name == "paper") return Profile::Paper;
  if (name == "linux") return Profile::Linux;
  fail(fmt::format("unknown profile '{}' (use \"paper\" or \"linux\")", name));
  return Profile::Linux;
}

// An index into an array for --set: digits only ("-1" or "+1" is no index), below `size`.
std::size_t array_index(const std::string& part, std::size_t size, const std::string& key, const std::string& source) {
  std::size_t index = 0;
  const char* end = part.data() + part.size();
  const auto [stop, error] = std::from_chars(part.data(), end, index);
  if (part.empty() || error != std::errc() || stop != end) {
    throw ConfigError(fmt::format("{}: --set '{}': '{}' is not an index into an array of {} (0 to {})", source, key, part, size,
                                  size == 0 ? std::string("none") : std::to_string(size - 1)));
  }
  if (index >= size) {
    throw ConfigError(fmt::format("{}: --set '{}': index {} is out of range (the array has {} element{})", source, key, index, size,
                                  size == 1 ? "" : "s"));
  }
  return index;
}

// --set KEY=VALUE: VALUE is read as a TOML value (16, 0.4, true, "50 GB"); anything that is not
// valid TOML is taken as a string, so --set pipelines.file_size=50GB works too.
toml::node_view<toml::node> ensure_path(toml::table& root, const std::string& key, const std::string& source) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  if (parts.empty() || key.back() == '.' || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    throw ConfigError(fmt::format("{}: --set '{}': not a dotted key such as pipelines.count", source, key));
  }
  toml::node* node = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (auto* table = node->as_table()) {
      if (!table->contains(part)) table->insert(part, toml::table{});
      node = table->get(part);
    } else if (auto* array = node->as_array()) {
      node = array->get(array_index(part, array->size(), key, source));
    } else {
      throw ConfigError(fmt::format("{}: --set '{}': '{}' is not a table", source, key, part));
    }
  }
  return toml::node_view<toml::node>(node);
}

void apply_override(toml::table& root, const std::string& key, const std::string& value, const std::string& source) {
  auto parent = ensure_path(root, key, source);
  const std::string last = key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
  // Parsed with the option as its source, so that a problem with the value names the option.
  const std::string option = fmt::format("--set {}={}", key, value);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, option);
  } catch (const toml::parse_error&) {
    // Not a TOML value: a string, written as a TOML string so that it has the option as its
    // source too.
    std::string quoted = "v = \"";
    for (const char c : value) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') quoted += '\\';
      if (byte < 0x20 || byte == 0x7f) quoted += fmt::format("\\u{:04X}", byte);
      else quoted += c;
    }
    try {
      parsed = toml::parse(quoted + "\"", option);
    } catch (const toml::parse_error& e) {
      throw ConfigError(fmt::format("{}: the value is not a TOML value, nor text ({})", option, e.description()));
    }
  }
  if (auto* table = parent.as_table()) {
    table->insert_or_assign(last, std::move(*parsed.get("v")));
  } else if (auto* array = parent.as_array()) {
    const std::size_t index = array_index(last, array->size(), key, source);
    array->replace(array->begin() + static_cast<std::ptrdiff_t>(index), std::move(*parsed.get("v")));
  } else {
    throw ConfigError(fmt::format("{}: --set '{}': cannot set a key there", source, key));
  }
}

}  // namespace

namespace {

CacheSettings read_page_cache(const toml::table* table, const TomlReader& parent, CacheSettings s, const std::string& file) {
  if (table == nullptr) return s;
  TomlReader r(*table, parent.child_path("page_cache"), file);
  if (auto mode = r.optional_string("mode")) {
    if (*mode == "writeback") s.write_mode = WriteMode::Writeback;
    else if (*mode == "writethrough") s.write_mode = WriteMode::Writethrough;
    else r.fail("mode", fmt::format("unknown mode '{}' (use \"writeback\" or \"writethrough\")", *mode));
  }
  auto ratio = [&](const char* key, double& out) {
    if (auto v = r.optional_number(key)) {
      if (!(*v >= 0.0 && *v <= 1.0)) r.fail(key, fmt::format("a ratio between 0 and 1, got {}", *v));
      out = *v;
    }
  };
  ratio("dirty_ratio", s.dirty_ratio);
  ratio("dirty_background_ratio", s.dirty_background_ratio);
  // Background writeback starting above the point where writers are stopped is a mistake
  // (the kernel quietly halves it); the key the scenario set is named.
  if (s.dirty_background_ratio > s.dirty_ratio) {
    const bool background_set = r.has("dirty_background_ratio");
    r.fail(background_set ? "dirty_background_ratio" : "dirty_ratio",
           fmt::format("dirty_background_ratio ({}{}) must not be above dirty_ratio ({}{})", s.dirty_background_ratio,
                       background_set ? "" : ", the profile's default", s.dirty_ratio, r.has("dirty_ratio") ? "" : ", the profile's default"));
  }
  if (auto v = r.optional_duration("dirty_expire")) s.dirty_expire = *v;
  if (auto v = r.optional_duration("writeback_interval")) {
    if (*v <= 0.0) r.fail("writeback_interval", "must be > 0");
    s.writeback_interval = *v;
  }
  // The decisions' model (docs/model.md §6), by default the profile's.
  const std::optional<std::string> policy = r.optional_string("policy");
  if (policy) {
    const std::vector<std::string> known = cache_policy_names();
    if (std::find(known.begin(), known.end(), *policy) == known.end()) {
      r.fail("policy", fmt::format("unknown policy '{}' (known: {})", *policy, fmt::join(known, ", ")));
    }
    s.policy = *policy;
  }
  // A policy's parameters: setting one chooses that policy, the others keeping the profile's
  // values (CacheSettings::set: under the paper profile, WRENCH-cache's).
  for (const PolicyDeclaration& owner : cache_policies()) {
    for (const PolicyParameter& parameter : owner.parameters) {
      const auto v = r.optional_bool(std::string(parameter.key));
      if (!v) continue;
      if (policy && *policy != owner.name) {
        r.fail(std::string(parameter.key), fmt::format("a parameter of the {} policy, and this host's policy is '{}'", owner.name, *policy));
      }
      if (s.policy != owner.name && find_cache_policy(s.policy)->preset_of != owner.name) s.policy = std::string(owner.name);
      s.set(parameter.key, *v);
    }
  }
  r.finish();
  return s;
}

// A rate whose 0 means "not modelled" (`zero`, said in the message): absent keeps `rate`.
void read_rate_or_zero(TomlReader& r, const char* key, double& rate, const char* zero) {
  rate = r.optional_bandwidth(key).value_or(rate);
  if (rate > 0.0 && rate < units::kMinBandwidth) r.fail(key, fmt::format("must be 0 ({}) or at least 1 B/s, got {} B/s", zero, rate));
}

// Free page reporting (docs/model.md §6.16): absent or "0 MB/s", no memory is taken back.
void read_free_page_reporting(TomlReader& r, HostConfig& h) {
  read_rate_or_zero(r, "memory_cold_fault_bw", h.memory_bandwidth.cold_fault, "no memory taken back");
  read_rate_or_zero(r, "memory_aggregate_cold_fault_bw", h.memory_bandwidth.aggregate_cold_fault, "memory_cold_fault_bw x cores");
  h.page_reporting_delay = r.optional_duration("page_reporting_delay").value_or(h.page_reporting_delay);
  if (!(h.page_reporting_delay >= 0.0)) r.fail("page_reporting_delay", "must be >= 0 s");
  h.memory_freed_at_start = r.optional_size("memory_freed_at_start").value_or(h.memory_freed_at_start);
  if (h.memory_freed_at_start < 0) r.fail("memory_freed_at_start", "must be >= 0");
}

// A disk's requests and write cache (DiskBandwidth): each absent or 0, not modelled. A table
// amending a disk keeps what it does not give, and the checks hold for the disk as amended.
void read_disk_requests(TomlReader& d, DiskSpec& disk) {
  disk.request_latency = d.optional_duration("request_latency").value_or(disk.request_latency);
  for (auto [key, bytes] : {std::pair{"read_ahead", &disk.read_ahead}, std::pair{"max_request", &disk.max_request}}) {
    *bytes = d.optional_size(key).value_or(*bytes);
    if (*bytes != 0 && *bytes < storage::kReadaheadPage) {
      d.fail(key, fmt::format("must be 0 (not modelled) or at least a page (4 KiB), got {} B", *bytes));
    }
  }
  disk.write_cache = d.optional_size("write_cache").value_or(disk.write_cache);
  disk.sustained_write_bw = d.optional_bandwidth("sustained_write_bw").value_or(disk.sustained_write_bw);
  const char* sustained = d.has("sustained_write_bw") ? "sustained_write_bw" : nullptr;
  if (disk.write_cache > 0 && disk.sustained_write_bw < units::kMinBandwidth) {
    d.fail(sustained != nullptr ? sustained : "write_cache",
           "a write cache needs sustained_write_bw, the rate at which the medium behind it takes the writes (at least 1 B/s)");
  }
  if (disk.write_cache == 0 && disk.sustained_write_bw > 0.0) {
    d.fail(sustained != nullptr ? sustained : "write_cache", "sustained_write_bw is the medium's rate behind a write cache: give write_cache too");
  }
  if (disk.sustained_write_bw > disk.write_bw) {
    d.fail(sustained != nullptr ? sustained : "write_bw",
           fmt::format("sustained_write_bw ({} B/s) must not be above write_bw ({} B/s): the cache takes writes faster than the medium",
                       disk.sustained_write_bw, disk.write_bw));
  }
}

// The keys of a [[hosts]] table. `base`: what is already known of the host, from a platform
// file (the table amends it: every key optional, its disks added or amended by name); without,
// memory and its bandwidths are required and the host needs a disk.
// A [[hosts]] table with `count` describes that many hosts alike, a host group (a cluster's
// nodes): each with its own page cache, named name-1 ... name-count. At most this many.
constexpr std::int64_t kMaxGroupHosts = 100'000;

HostConfig read_host(const toml::table& table, std::string path, std::size_t index, Profile profile, const std::string& file,
                     const HostConfig* base, Origin& host_origin, Origin& cache_origin, std::vector<Origin>& disk_origins,
                     std::int64_t* count = nullptr) {
  TomlReader r(table, std::move(path), file);
  host_origin = {&table, r.path(), &file};
  const bool fresh = base == nullptr;
  HostConfig h = fresh ? HostConfig{} : *base;
  if (fresh) h.cache = settings_for(profile);
  h.name = fresh ? r.name("name", fmt::format("host{}", index + 1)) : r.name("name", h.name);
  h.cores = static_cast<int>(r.optional_integer("cores", 1, 1'000'000).value_or(h.cores));
  h.memory_in_use = r.optional_size("memory_in_use").value_or(h.memory_in_use);
  h.memory = fresh ? r.required_size("memory") : r.optional_size("memory").value_or(h.memory);
  if (r.has("memory") && h.memory <= 0) r.fail("memory", "must be > 0");
  if (h.memory > 0 && h.memory_in_use >= h.memory) r.fail("memory_in_use", "must be less than the memory");
  MemoryBandwidth& bw = h.memory_bandwidth;
  bw.read = fresh ? r.required_bandwidth("memory_read_bw") : r.optional_bandwidth("memory_read_bw").value_or(bw.read);
  bw.write = fresh ? r.required_bandwidth("memory_write_bw") : r.optional_bandwidth("memory_write_bw").value_or(bw.write);
  bw.aggregate_read = r.optional_bandwidth("memory_aggregate_read_bw").value_or(fresh || r.has("memory_read_bw") ? bw.read : bw.aggregate_read);
  bw.aggregate_write =
      r.optional_bandwidth("memory_aggregate_write_bw").value_or(fresh || r.has("memory_write_bw") ? bw.write : bw.aggregate_write);
  for (const auto& [key, value] : {std::pair{"memory_aggregate_read_bw", bw.aggregate_read}, std::pair{"memory_aggregate_write_bw", bw.aggregate_write}}) {
    if (r.has(key) && value < units::kMinBandwidth) r.fail(key, fmt::format("must be at least 1 B/s, got {} B/s", value));
  }
  read_rate_or_zero(r, "memory_first_touch_bw", bw.first_touch, "free");
  read_rate_or_zero(r, "memory_reclaimed_write_bw", bw.reclaimed_write, "as into free pages");
  read_free_page_reporting(r, h);
  const toml::table* page_cache = r.optional_table("page_cache");
  h.cache = read_page_cache(page_cache, r, h.cache, file);
  if (page_cache != nullptr || fresh) cache_origin = page_cache != nullptr ? Origin{page_cache, r.child_path("page_cache"), &file} : host_origin;
  const auto disks = r.tables("disks");
  if (fresh) disk_origins.clear();
  std::set<std::string> named;  // by this table
  for (std::size_t i = 0; i < disks.size(); ++i) {
    TomlReader d(*disks[i], r.child_path("disks", i), file);
    const std::string name = d.name("name", fmt::format("disk{}", h.disks.size() + 1));
    if (!named.insert(name).second) d.fail("name", fmt::format("host '{}' has two disks named '{}'", h.name, name));
    const auto known = std::find_if(h.disks.begin(), h.disks.end(), [&](const DiskSpec& x) { return x.name == name; });
    const bool amend = known != h.disks.end();
    DiskSpec disk = amend ? *known : DiskSpec{};
    disk.name = name;
    disk.read_bw = amend ? d.optional_bandwidth("read_bw").value_or(disk.read_bw) : d.required_bandwidth("read_bw");
    disk.write_bw = amend ? d.optional_bandwidth("write_bw").value_or(disk.write_bw) : d.required_bandwidth("write_bw");
    // Several streams together (absent: as fast as one); never below one stream's.
    for (auto [key, aggregate, stream] : {std::tuple{"aggregate_read_bw", &disk.aggregate_read_bw, disk.read_bw},
                                          std::tuple{"aggregate_write_bw", &disk.aggregate_write_bw, disk.write_bw}}) {
      *aggregate = d.optional_bandwidth(key).value_or(*aggregate);
      if (*aggregate > 0.0 && *aggregate < stream) {
        d.fail(key, fmt::format("must not be below one stream's bandwidth ({} B/s), got {} B/s", stream, *aggregate));
      }
    }
    disk.capacity = d.optional_size("capacity").value_or(disk.capacity);
    read_disk_requests(d, disk);
    d.finish();
    const Origin origin{disks[i], d.path(), &file};
    if (amend) {
      disk_origins[static_cast<std::size_t>(known - h.disks.begin())] = origin;
      *known = std::move(disk);
    } else {
      disk_origins.push_back(origin);
      h.disks.push_back(std::move(disk));
    }
  }
  if (fresh && h.disks.empty()) r.fail_table(fmt::format("host '{}' has no disk ([[{}.disks]])", h.name, r.path()));
  if (count != nullptr) {
    *count = r.optional_integer("count", 1, kMaxGroupHosts).value_or(0);
  } else if (r.has("count")) {
    r.fail("count", "a host amending a platform file's is one host: give count where the hosts are first described");
  }
  r.finish();
  return h;
}

// memory_max / memory_high: the limits of a memory group (`whose`: whose, for the message).
// Absent: `inherited` (a workflow's for its tasks), unless memory_max is given here.
MemoryLimits read_memory_limits(TomlReader& r, const char* whose, MemoryLimits inherited = {}) {
  MemoryLimits m = r.has("memory_max") ? MemoryLimits{} : inherited;
  m.max = r.optional_size("memory_max").value_or(m.max);
  if (r.has("memory_max") && m.max <= 0) r.fail("memory_max", fmt::format("must be > 0 ({} memory group's limit)", whose));
  m.high = r.optional_size("memory_high").value_or(m.high);
  if (r.has("memory_high") && (m.high <= 0 || m.max == 0 || m.high > m.max)) {
    r.fail("memory_high", "must be > 0 and at most memory_max, which it needs");
  }
  return m;
}

TaskSpec read_task(const toml::table& table, std::string path, std::size_t index, std::int64_t default_chunk,
                   const std::string& file, bool in_workflow, MemoryLimits workflow_limits = {}) {
  TomlReader r(table, std::move(path), file);
  TaskSpec t;
  t.name = r.name("name", std::to_string(index + 1));
  if (in_workflow) {
    t.host = r.name("host", "");
    t.cores = static_cast<int>(r.optional_integer("cores", 1, 1'000'000).value_or(1));
  }
  t.memory = r.optional_size("memory").value_or(0);
  t.reads = r.names("read");
  t.compute = r.optional_duration("compute").value_or(0.0);
  t.writes = r.names("write");
  t.chunk_size = r.optional_size("chunk_size").value_or(default_chunk);
  if (t.chunk_size <= 0) r.fail("chunk_size", "must be > 0");
  if (in_workflow) {
    t.after = r.names("after");
    t.memory_limits = read_memory_limits(r, "the task's", workflow_limits);
  }
  t.fsync = r.optional_bool("fsync").value_or(false);
  t.direct_io = r.optional_bool("direct_io").value_or(false);
  t.deletes = r.names("delete");
  r.finish();
  return t;
}

// [pipelines]: N identical concurrent pipelines of T tasks; task k of pipeline i reads
// file k and writes file k+1 of that pipeline ("file_k" when N = 1, else "p<i>_file_k").
void expand_pipelines(const toml::table& table, Scenario& s, const std::string& file, const ScenarioLimits& limits,
                      Origins& origins) {
  TomlReader r(table, "pipelines", file);
  origins.pipelines = Origin{&table, "pipelines", &file};
  const std::int64_t count = r.optional_integer("count").value_or(1);
  if (count < 1) r.fail("count", "must be >= 1");
  const std::string host = r.name("host", s.hosts.empty() ? std::string() : s.hosts.front().name);
  const std::string files_host = r.name("files_host", host);
  std::string disk = r.name("disk", "");
  const std::int64_t size = r.required_size("file_size");
  const std::int64_t tasks = r.optional_integer("tasks").value_or(3);
  if (tasks < 1) r.fail("tasks", "must be >= 1");
  // Checked before anything is made: a count of 10^9 would otherwise fill the memory first.
  // Doubles, so that the products cannot overflow.
  const double task_total = static_cast<double>(count) * static_cast<double>(tasks) + static_cast<double>(s.apps.size());
  const double file_total = static_cast<double>(count) * (static_cast<double>(tasks) + 1.0) + static_cast<double>(s.files.size());
  const char* culprit = tasks > count ? "tasks" : "count";
  if (task_total > static_cast<double>(limits.max_tasks)) {
    r.fail(culprit, fmt::format("{} pipelines of {} tasks are {:.3g} tasks, more than the {} a run may have{}", count, tasks, task_total,
                                limits.max_tasks, scenario::limits_hint(limits)));
  }
  if (file_total > static_cast<double>(limits.max_files)) {
    r.fail(culprit, fmt::format("{} pipelines of {} tasks use {:.3g} files, more than the {} a run may have{}", count, tasks, file_total,
                                limits.max_files, scenario::limits_hint(limits)));
  }
  const double cpu = r.optional_duration("cpu_time").value_or(0.0);
  const std::int64_t chunk = r.optional_size("chunk_size").value_or(100'000'000);
  if (chunk <= 0) r.fail("chunk_size", "must be > 0");
  const bool cached = r.optional_bool("inputs_cached").value_or(false);
  const MemoryLimits memory_limits = read_memory_limits(r, "a pipeline's");
  r.finish();
  // A host group: the pipelines spread over its members in blocks (pipeline i on member
  // ceil(i * members / count)), each member's page cache its own.
  const auto group = origins.host_groups.find(host);
  if (group == origins.host_groups.end() && std::none_of(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == host; })) {
    r.fail("host", fmt::format("no host named '{}'", host));
  }
  const auto host_of = [&](std::int64_t i) -> const std::string& {
    if (group == origins.host_groups.end()) return host;
    const auto [first, members] = group->second;
    return s.hosts[first + static_cast<std::size_t>((i - 1) * static_cast<std::int64_t>(members) / count)].name;
  };
  if (origins.host_groups.count(files_host) != 0) {
    r.fail(r.has("files_host") ? "files_host" : "host",
           fmt::format("'{}' is a host group: the pipelines' files are on one host (files_host = \"...\")", files_host));
  }
  const auto h = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == files_host; });
  if (h == s.hosts.end()) r.fail("files_host", fmt::format("no host named '{}'", files_host));
  if (disk.empty()) {
    if (h->disks.empty()) r.fail("files_host", fmt::format("host '{}' has no disk to store the pipelines' files", files_host));
    disk = h->disks.front().name;
  }
  s.files.reserve(s.files.size() + static_cast<std::size_t>(count * (tasks + 1)));
  s.apps.reserve(s.apps.size() + static_cast<std::size_t>(count));
  for (std::int64_t i = 1; i <= count; ++i) {
    auto file_name = [&](std::int64_t k) { return count == 1 ? fmt::format("file_{}", k) : fmt::format("p{}_file_{}", i, k); };
    for (std::int64_t k = 1; k <= tasks + 1; ++k) s.files.push_back({file_name(k), size, files_host, disk, k == 1 && cached});
    AppSpec app{std::to_string(i), host_of(i), {}, memory_limits.max, memory_limits.high};
    app.tasks.reserve(static_cast<std::size_t>(tasks));
    for (std::int64_t k = 1; k <= tasks; ++k) {
      TaskSpec& task = app.tasks.emplace_back();
      task.name = std::to_string(k);
      task.reads = {file_name(k)};
      task.compute = cpu;
      task.writes = {file_name(k + 1)};
      task.chunk_size = chunk;
    }
    s.apps.push_back(std::move(app));
  }
  origins.pipeline_apps = static_cast<std::size_t>(count);
}

// A cycle of dependencies, reported with its tasks. Iterative: a workflow may be a chain of
// 10^5 tasks, deeper than the stack a recursive search would need. `tasks`: where each task
// is; a workflow file's (JSON) are named there, its tasks having no TOML table.
void check_workflow_acyclic(const WorkflowSpec& w, const Origin& r, const std::vector<Origin>& tasks) {
  std::map<std::string, std::size_t> by_name;
  std::map<std::string, std::size_t> producer;
  for (std::size_t i = 0; i < w.tasks.size(); ++i) {
    if (!by_name.emplace(w.tasks[i].name, i).second) r.fail("tasks", fmt::format("two tasks named '{}'", w.tasks[i].name));
    for (const auto& f : w.tasks[i].writes) {
      const auto [first, added] = producer.emplace(f, i);
      if (added) continue;
      if (!w.source.empty()) {
        tasks[i].fail_table(fmt::format("file '{}' is written by two tasks, '{}' and '{}'", f, w.tasks[first->second].name, w.tasks[i].name));
      }
      r.fail("tasks", fmt::format("file '{}' is written by two tasks", f));
    }
  }
  std::vector<std::vector<std::size_t>> deps(w.tasks.size());
  for (std::size_t i = 0; i < w.tasks.size(); ++i) {
    for (const auto& a : w.tasks[i].after) {
      auto it = by_name.find(a);
      if (it == by_name.end()) r.fail("tasks", fmt::format("task '{}' comes after an unknown task '{}'", w.tasks[i].name, a));
      deps[i].push_back(it->second);
    }
    for (const auto& f : w.tasks[i].reads) {
      if (auto it = producer.find(f); it != producer.end()) deps[i].push_back(it->second);
    }
  }
  enum : char { Unseen, OnPath, Done };
  std::vector<char> state(w.tasks.size(), Unseen);
  std::vector<std::pair<std::size_t, std::size_t>> path;  // (task, next dependency to visit)
  for (std::size_t root = 0; root < w.tasks.size(); ++root) {
    if (state[root] != Unseen) continue;
    state[root] = OnPath;
    path.emplace_back(root, 0);
    while (!path.empty()) {
      auto& [task, next] = path.back();
      if (next == deps[task].size()) {
        state[task] = Done;
        path.pop_back();
        continue;
      }
      const std::size_t d = deps[task][next++];
      if (state[d] == OnPath) {
        std::string cycle;
        auto it = std::find_if(path.begin(), path.end(), [&](const auto& p) { return p.first == d; });
        for (; it != path.end(); ++it) cycle += w.tasks[it->first].name + " -> ";
        r.fail("tasks", fmt::format("dependency cycle: {}{}", cycle, w.tasks[d].name));
      }
      if (state[d] == Unseen) {
        state[d] = OnPath;
        path.emplace_back(d, 0);
      }
    }
  }
}

// The platform part of a scenario or of a platform file: [[hosts]] and [[links]].
void read_platform(TomlReader& r, Scenario& s, const std::string& file, Origins& origins, std::set<std::size_t>& amendable) {
  const auto hosts = r.tables("hosts");
  std::unordered_set<std::string> named;  // hosts so far, for names given twice
  for (const HostConfig& h : s.hosts) named.insert(h.name);
  for (std::size_t i = 0; i < hosts.size(); ++i) {
    // A host of a platform's XML file is amended by a [[hosts]] table of its name.
    const std::string name = (*hosts[i])["name"].value<std::string>().value_or("");
    const auto known = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == name; });
    const std::size_t at = static_cast<std::size_t>(known - s.hosts.begin());
    if (known != s.hosts.end() && amendable.count(at) != 0) {
      amendable.erase(at);  // once
      *known = read_host(*hosts[i], r.child_path("hosts", i), at, s.profile, file, &*known, origins.hosts[at], origins.page_caches[at],
                         origins.disks[at]);
      continue;
    }
    Origin host_origin, cache_origin;
    std::vector<Origin> disk_origins;
    std::int64_t count = 0;
    HostConfig host = read_host(*hosts[i], r.child_path("hosts", i), s.hosts.size(), s.profile, file, nullptr, host_origin, cache_origin,
                                disk_origins, &count);
    const auto taken = [&](const std::string& candidate) { return origins.host_groups.count(candidate) != 0 || named.count(candidate) != 0; };
    if (taken(host.name)) TomlReader(*hosts[i], r.child_path("hosts", i), file).fail("name", "two hosts share this name");
    if (count == 0) {
      origins.hosts.push_back(std::move(host_origin));
      origins.page_caches.push_back(std::move(cache_origin));
      origins.disks.push_back(std::move(disk_origins));
      named.insert(host.name);
      s.hosts.push_back(std::move(host));
      continue;
    }
    // A group: its members are hosts like any other, named after it; the group's name stands
    // for them all where a link or the pipelines name it.
    const std::string group = host.name;
    for (std::int64_t k = 1; k <= count; ++k) {
      if (taken(fmt::format("{}-{}", group, k))) {
        TomlReader(*hosts[i], r.child_path("hosts", i), file).fail("name", fmt::format("host '{}-{}' of this group is named twice", group, k));
      }
    }
    origins.host_groups[group] = {s.hosts.size(), static_cast<std::size_t>(count)};
    s.hosts.reserve(s.hosts.size() + static_cast<std::size_t>(count));
    for (std::int64_t k = 1; k <= count; ++k) {
      origins.hosts.push_back(host_origin);
      origins.page_caches.push_back(cache_origin);
      origins.disks.push_back(disk_origins);
      HostConfig& member = s.hosts.emplace_back(host);
      member.name = fmt::format("{}-{}", group, k);
      named.insert(member.name);
    }
  }
  // By name and by pair, not by scanning: a platform shown from a cluster run has 10^4 of each.
  std::set<std::string> host_names, link_names;
  std::set<std::pair<std::string, std::string>> joined;  // hosts with a link or route, each pair in order
  for (const HostConfig& h : s.hosts) host_names.insert(h.name);
  for (const LinkSpec& l : s.links) {
    link_names.insert(l.name);
    if (!l.host_a.empty()) joined.insert(std::minmax(l.host_a, l.host_b));
  }
  for (const RouteSpec& rs : s.routes) joined.insert(std::minmax(rs.host_a, rs.host_b));
  // hosts = ["a", "b"] of a link or route: two different known hosts not joined yet.
  const auto read_ends = [&](TomlReader& t, const char* what) {
    const std::vector<std::string> ends = t.names("hosts");
    if (ends.size() != 2 || ends[0] == ends[1]) t.fail("hosts", fmt::format("a {} joins two different hosts: hosts = [\"a\", \"b\"]", what));
    for (const std::string& end : ends) {
      if (host_names.count(end) == 0) t.fail("hosts", fmt::format("no host named '{}'", end));
    }
    if (!joined.insert(std::minmax(ends[0], ends[1])).second) t.fail("hosts", "these hosts already have a link or a route");
    return std::pair{ends[0], ends[1]};
  };
  const auto links = r.tables("links");
  for (std::size_t i = 0; i < links.size(); ++i) {
    TomlReader l(*links[i], r.child_path("links", i), file);
    origins.links.push_back({links[i], l.path(), &file});
    LinkSpec link;
    link.name = l.name("name", fmt::format("link{}", s.links.size() + 1));
    link.bandwidth = l.required_bandwidth("bandwidth");
    link.latency = l.optional_duration("latency").value_or(0.0);
    if (auto sharing = l.optional_string("sharing")) {
      if (*sharing == "fatpipe") link.sharing = LinkSharing::Fatpipe;
      else if (*sharing != "shared") l.fail("sharing", fmt::format("unknown sharing '{}' (use \"shared\" or \"fatpipe\")", *sharing));
    }
    if (!link_names.insert(link.name).second) l.fail("name", fmt::format("two links named '{}'", link.name));
    // A host group at one end: a link of its own for each member, named after the link.
    const std::vector<std::string> ends = l.has("hosts") ? l.names("hosts") : std::vector<std::string>{};
    const auto group = ends.size() == 2 ? std::find_if(ends.begin(), ends.end(), [&](const std::string& e) { return origins.host_groups.count(e) != 0; })
                                        : ends.end();
    if (group == ends.end()) {
      // Without hosts, a link is crossed only by the routes that name it.
      if (l.has("hosts")) std::tie(link.host_a, link.host_b) = read_ends(l, "link");
      l.finish();
      s.links.push_back(std::move(link));
      continue;
    }
    const std::string& other = *group == ends[0] ? ends[1] : ends[0];
    if (origins.host_groups.count(other) != 0) l.fail("hosts", "a link joins a host group to one host, not two groups");
    if (host_names.count(other) == 0) l.fail("hosts", fmt::format("no host named '{}'", other));
    l.finish();
    const auto [first, count] = origins.host_groups.at(*group);
    for (std::size_t k = 0; k < count; ++k) {
      LinkSpec& member = s.links.emplace_back(link);
      member.name = fmt::format("{}-{}", link.name, k + 1);
      member.host_a = s.hosts[first + k].name;
      member.host_b = other;
      if (!link_names.insert(member.name).second) l.fail("name", fmt::format("two links named '{}'", member.name));
      if (!joined.insert(std::minmax(member.host_a, member.host_b)).second) {
        l.fail("hosts", fmt::format("hosts '{}' and '{}' already have a link or a route", member.host_a, member.host_b));
      }
      const Origin origin = origins.links.back();
      origins.links.push_back(origin);
    }
    origins.links.pop_back();  // one per link made
  }
  const auto routes = r.tables("routes");
  for (std::size_t i = 0; i < routes.size(); ++i) {
    TomlReader rt(*routes[i], r.child_path("routes", i), file);
    origins.routes.push_back({routes[i], rt.path(), &file});
    RouteSpec route;
    std::tie(route.host_a, route.host_b) = read_ends(rt, "route");
    route.links = rt.names("links");
    if (route.links.empty()) rt.fail("links", "a route crosses at least one link");
    for (const std::string& name : route.links) {
      if (link_names.count(name) == 0) rt.fail("links", fmt::format("no link named '{}'", name));
    }
    rt.finish();
    s.routes.push_back(std::move(route));
  }
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


// A path written in `file`, relative to its folder.
std::string relative_path(const std::string& file, const std::string& path) {
  const std::filesystem::path relative_to = std::filesystem::path(file).parent_path();
  return std::filesystem::path(path).is_absolute() ? path : (relative_to / path).lexically_normal().string();
}

// A SimGrid platform: named .xml, or XML inside (a byte-order mark and spaces aside).
bool is_xml_file(const std::string& path, const std::string& text) {
  if (std::filesystem::path(path).extension() == ".xml") return true;
  std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n')) ++i;
  return i < text.size() && text[i] == '<';
}

// [host_defaults]: for the hosts of a SimGrid platform, what its file does not say. Memory and
// memory bandwidths fill in where the file gives none; the rest (no SimGrid word for them)
// applies to every such host. A [[hosts]] table of a host's name amends it after.
void apply_host_defaults(const toml::table& table, const std::string& file, const std::set<std::size_t>& hosts, Scenario& s,
                         Origins& origins) {
  TomlReader r(table, "host_defaults", file);
  const auto memory = r.optional_size("memory");
  if (memory && *memory <= 0) r.fail("memory", "must be > 0");
  const auto in_use = r.optional_size("memory_in_use");
  const auto read = r.optional_bandwidth("memory_read_bw");
  const auto write = r.optional_bandwidth("memory_write_bw");
  const auto aggregate_read = r.optional_bandwidth("memory_aggregate_read_bw");
  const auto aggregate_write = r.optional_bandwidth("memory_aggregate_write_bw");
  const auto first_touch = r.optional_bandwidth("memory_first_touch_bw");
  if (first_touch && *first_touch > 0.0 && *first_touch < units::kMinBandwidth) {
    r.fail("memory_first_touch_bw", fmt::format("must be 0 (free) or at least 1 B/s, got {} B/s", *first_touch));
  }
  const auto reclaimed_write = r.optional_bandwidth("memory_reclaimed_write_bw");
  if (reclaimed_write && *reclaimed_write > 0.0 && *reclaimed_write < units::kMinBandwidth) {
    r.fail("memory_reclaimed_write_bw", fmt::format("must be 0 (as into free pages) or at least 1 B/s, got {} B/s", *reclaimed_write));
  }
  const toml::table* page_cache = r.optional_table("page_cache");
  for (const std::size_t i : hosts) {
    HostConfig& h = s.hosts[i];
    if (h.memory == 0 && memory) h.memory = *memory;
    if (in_use) h.memory_in_use = *in_use;
    if (h.memory > 0 && h.memory_in_use >= h.memory) {
      r.fail("memory_in_use", fmt::format("must be less than the memory of host '{}' ({})", h.name, units::format_size(h.memory)));
    }
    MemoryBandwidth& bw = h.memory_bandwidth;
    if (bw.read == 0.0 && read) bw.read = bw.aggregate_read = *read;
    if (bw.write == 0.0 && write) bw.write = bw.aggregate_write = *write;
    if (aggregate_read) bw.aggregate_read = *aggregate_read;
    if (aggregate_write) bw.aggregate_write = *aggregate_write;
    if (first_touch) bw.first_touch = *first_touch;
    if (reclaimed_write) bw.reclaimed_write = *reclaimed_write;
    h.cache = read_page_cache(page_cache, r, h.cache, file);
    if (page_cache != nullptr) origins.page_caches[i] = Origin{page_cache, r.child_path("page_cache"), &file};
  }
  r.finish();
}

// workflow = "x.json", or [workflow] with file = "x.json": a workflow instance and its options.
void read_workflow_file(TomlReader& root, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins) {
  const toml::node* node = root.raw("workflow");
  scenario::WorkflowImport options;
  std::string path;
  std::optional<TomlReader> table;
  if (node->is_string()) {
    path = *node->value<std::string>();
    origins.workflows.push_back(origins.root);
  } else {
    table.emplace(*node->as_table(), "workflow", file);
    origins.workflows.push_back({node->as_table(), "workflow", &file});
    path = table->required_string("file");
    options.name = table->name("name", "");
    options.files_host = table->name("files_host", "");
    options.files_disk = table->name("files_disk", "");
    options.hosts = table->names("hosts");
    if (table->has("hosts") && options.hosts.empty()) table->fail("hosts", "at least one host");
    options.inputs_cached = table->optional_bool("inputs_cached").value_or(false);
    if (auto compute = table->optional_string("compute")) {
      if (*compute == "runtime") options.compute = scenario::ComputeFrom::Runtime;
      else if (*compute == "cpu_share") options.compute = scenario::ComputeFrom::CpuShare;
      else table->fail("compute", fmt::format("unknown '{}' (use \"runtime\" or \"cpu_share\")", *compute));
    }
    options.chunk_size = table->optional_size("chunk_size").value_or(options.chunk_size);
    if (options.chunk_size <= 0) table->fail("chunk_size", "must be > 0");
    options.memory_limits = read_memory_limits(*table, "each task's");
  }
  const std::string json = relative_path(file, path);
  const auto fail = [&](const std::string& key, const std::string& message) {
    // Not given, and the table has no place in a file (pcsim's options made it: load_workflow):
    // the workflow file decided it.
    if (table && !table->has(key) && node->source().begin.line == 0) throw ConfigError(fmt::format("{}: {}", json, message));
    if (table) table->fail(key, message);
    root.fail("workflow", message);
  };
  std::string text;
  try {
    text = scenario::read_text_file(json, "workflow file");
  } catch (const ConfigError& e) {
    if (table) table->fail("file", e.what());
    root.fail("workflow", e.what());
  }
  const scenario::WfWorkflow workflow = scenario::read_workflow_json(text, json, limits.max_tasks, limits.max_files);
  scenario::add_json_workflow(workflow, options, s, origins, fail);
  if (table) table->finish();
  check_workflow_acyclic(s.workflows.back(), origins.workflows.back(), origins.workflow_tasks.back());
}

// A run on a SimGrid platform keeps what it uses: the hosts that run tasks or store files, the
// routes between them and the links those cross (a cluster's N^2 routes are never listed). The
// hosts it keeps must say what the model needs of them.
void keep_what_the_run_uses(const scenario::SgPlatform& platform, const std::set<std::size_t>& from_xml, Scenario& s, Origins& origins) {
  std::set<std::string> runs, stores;
  for (const AppSpec& a : s.apps) runs.insert(a.host);
  for (const WorkflowSpec& w : s.workflows) {
    runs.insert(w.hosts.begin(), w.hosts.end());
    for (const TaskSpec& t : w.tasks) {
      if (!t.host.empty()) runs.insert(t.host);
    }
  }
  for (const FileSpec& f : s.files) stores.insert(f.host);
  std::set<std::pair<std::string, std::string>> pairs;
  for (const std::string& a : runs) {
    for (const std::string& b : stores) pairs.emplace(a, b);
  }
  const std::size_t routes_before = s.routes.size();
  scenario::add_simgrid_routes(platform, pairs, s);
  for (std::size_t i = routes_before; i < s.routes.size(); ++i) origins.routes.push_back(Origin::elsewhere(platform.file + ": route"));

  std::set<std::string> crossed;
  for (const RouteSpec& r : s.routes) crossed.insert(r.links.begin(), r.links.end());
  std::vector<LinkSpec> links;
  std::vector<Origin> link_origins;
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const bool from_platform = l < platform.links.size();
    if (!from_platform || crossed.count(s.links[l].name) != 0) {
      links.push_back(std::move(s.links[l]));
      link_origins.push_back(std::move(origins.links[l]));
    }
  }
  s.links = std::move(links);
  origins.links = std::move(link_origins);
  scenario::add_link_warnings(platform, s);

  std::vector<HostConfig> hosts;
  Origins kept = origins;
  kept.hosts.clear(), kept.page_caches.clear(), kept.disks.clear();
  for (std::size_t h = 0; h < s.hosts.size(); ++h) {
    HostConfig& host = s.hosts[h];
    const bool used = runs.count(host.name) != 0 || stores.count(host.name) != 0;
    if (from_xml.count(h) != 0 && !used) continue;
    if (from_xml.count(h) != 0) {
      const Origin& o = origins.hosts[h];
      const std::string amend = fmt::format("in [host_defaults], or in a [[hosts]] table named '{}', of a scenario", host.name);
      if (host.memory <= 0) {
        o.fail_table(fmt::format("no memory size: give the host a <prop id=\"ram\" value=\"...\"/> (WRENCH's convention), or memory {}", amend));
      }
      if (host.memory_bandwidth.read <= 0.0 || host.memory_bandwidth.write <= 0.0) {
        o.fail_table(fmt::format("no memory bandwidth: give the host a <disk> mounted at /memory (WRENCH-cache's convention), or "
                                 "memory_read_bw and memory_write_bw {}",
                                 amend));
      }
      if (host.memory_in_use >= host.memory) o.fail_table("memory_in_use must be less than the memory");
    }
    kept.hosts.push_back(origins.hosts[h]);
    kept.page_caches.push_back(origins.page_caches[h]);
    kept.disks.push_back(origins.disks[h]);
    hosts.push_back(std::move(host));
  }
  s.hosts = std::move(hosts);
  origins = std::move(kept);
}

// `platform_only`: a platform file shown alone (pcsim show PLATFORM): no workload, and what a run
// would need of the hosts (memory sizes and bandwidths) may be missing.
// `platform_overrides`: --set keys of the platform's hosts, links and routes, for a scenario
// that takes them from a TOML platform file (see parse_scenario).
Scenario resolve(const toml::table& root, const std::string& file, const std::string& profile_override, const ScenarioLimits& limits,
                 bool platform_only = false, const Overrides& platform_overrides = {}) {
  TomlReader r(root, "", file);
  Origins origins;
  origins.root = {&root, "", &file};
  Scenario s;
  s.source = file;
  s.title = r.string("title", "");
  const std::string file_profile = r.string("profile", "linux");
  if (profile_override.empty()) {
    s.profile = parse_profile(file_profile, [&](const std::string& m) { r.fail("profile", m); });
  } else {
    s.profile = parse_profile(profile_override, [](const std::string& m) -> void { throw ConfigError("--profile: " + m); });
  }
  s.memory_sample_interval = r.optional_duration("memory_sample_interval").value_or(1.0);
  s.trace = r.optional_bool("trace").value_or(false);

  // platform = "file.toml" or "file.xml" (SimGrid), or one per profile:
  // platform = { paper = "a.toml", linux = "b.toml" }
  std::string platform_file;  // outlives the platform's origins
  toml::table platform_root;
  std::optional<scenario::SgPlatform> simgrid;  // kept until the run's routes are known
  std::set<std::size_t> amendable;              // hosts of an XML platform, which [[hosts]] tables amend
  if (const toml::node* platform = r.raw("platform")) {
    std::string path;
    if (platform->is_string()) {
      path = *platform->value<std::string>();
    } else if (const toml::table* per_profile = platform->as_table()) {
      const toml::node* chosen = per_profile->get(to_string(s.profile));
      if (chosen == nullptr || !chosen->is_string()) r.fail("platform", fmt::format("no platform file for profile '{}'", to_string(s.profile)));
      path = *chosen->value<std::string>();
    } else {
      r.fail("platform", "expected a file name, or a table of file names per profile");
    }
    platform_file = relative_path(file, path);
    std::string text;
    try {
      text = scenario::read_text_file(platform_file, "platform file");
    } catch (const ConfigError& e) {
      r.fail("platform", e.what());
    }
    if (is_xml_file(platform_file, text)) {
      if (!platform_overrides.empty()) {
        throw ConfigError(fmt::format("--set {}: the hosts, links and routes come from a SimGrid platform file ({}): amend a host with a "
                                      "[[hosts]] table naming it", platform_overrides.front().first, platform_file));
      }
      simgrid = scenario::read_simgrid_platform(text, platform_file);
      scenario::add_simgrid_platform(*simgrid, s, origins);
      for (std::size_t h = 0; h < s.hosts.size(); ++h) amendable.insert(h);
    } else {
      try {
        platform_root = toml::parse(text, platform_file);
      } catch (const toml::parse_error& e) {
        throw ConfigError(fmt::format("{}:{}:{}: {}", platform_file, e.source().begin.line, e.source().begin.column, e.description()));
      }
      for (const auto& [key, value] : platform_overrides) apply_override(platform_root, key, value, platform_file);
      TomlReader p(platform_root, "", platform_file);
      p.string("title", "");
      read_platform(p, s, platform_file, origins, amendable);
      p.finish();
    }
  }
  const std::set<std::size_t> from_xml = amendable;
  if (const toml::table* defaults = r.optional_table("host_defaults")) {
    if (from_xml.empty()) r.fail("host_defaults", "fills in what a SimGrid platform file does not say; this scenario has none");
    apply_host_defaults(*defaults, file, from_xml, s, origins);
  }
  read_platform(r, s, file, origins, amendable);
  if (s.hosts.empty()) r.fail_table("no host: add a [[hosts]] table, or a platform file");

  // [start.memory_in_use]: host name -> memory in use when this run starts (what a measured
  // run began with, e.g. tmpfs contents), replacing the platform's figure for that host.
  if (const toml::table* start = r.optional_table("start")) {
    TomlReader st(*start, "start", file);
    if (const toml::table* in_use = st.optional_table("memory_in_use")) {
      TomlReader m(*in_use, "start.memory_in_use", file);
      for (const auto& [key, node] : *in_use) {
        const std::string name(key.str());
        const auto h = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == name; });
        if (h == s.hosts.end()) m.fail(name, fmt::format("no host named '{}'", name));
        h->memory_in_use = *m.optional_size(name);
        if (h->memory_in_use >= h->memory) m.fail(name, "must be less than the host's memory");
      }
      m.finish();
    }
    st.finish();
  }

  const auto files = r.tables("files");
  for (std::size_t i = 0; i < files.size(); ++i) {
    TomlReader f(*files[i], r.child_path("files", i), file);
    origins.files.push_back({files[i], f.path(), &file});
    FileSpec spec;
    spec.name = f.required_name("name");
    spec.size = f.required_size("size");
    spec.host = f.name("host", s.hosts.front().name);
    spec.disk = f.name("disk", "");
    spec.cached = f.optional_bool("cached").value_or(false);
    const auto h = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == spec.host; });
    if (h == s.hosts.end()) f.fail("host", fmt::format("no host named '{}'", spec.host));
    if (spec.disk.empty()) {
      // A platform file's host may have none (a SimGrid cluster's).
      if (h->disks.empty()) f.fail("host", fmt::format("host '{}' has no disk to store file '{}'", spec.host, spec.name));
      spec.disk = h->disks.front().name;
    }
    f.finish();
    s.files.push_back(std::move(spec));
  }
  // workflow = "x.json", or [workflow] with file = "x.json" and options: a WfFormat instance.
  // Read before [pipelines], whose files' origins are all that table's (Origins::file).
  const toml::node* workflow_node = root.get("workflow");
  const toml::table* workflow_table = workflow_node != nullptr ? workflow_node->as_table() : nullptr;
  if (workflow_node != nullptr && (workflow_node->is_string() || (workflow_table != nullptr && workflow_table->contains("file")))) {
    read_workflow_file(r, s, file, limits, origins);
  }
  if (const toml::table* p = r.optional_table("pipelines")) expand_pipelines(*p, s, file, limits, origins);

  const auto apps = r.tables("apps");
  for (std::size_t i = 0; i < apps.size(); ++i) {
    TomlReader a(*apps[i], r.child_path("apps", i), file);
    origins.apps.push_back({apps[i], a.path(), &file});
    std::vector<Origin>& task_origins = origins.app_tasks.emplace_back();
    AppSpec app;
    app.name = a.name("name", fmt::format("app{}", i + 1));
    app.host = a.name("host", s.hosts.front().name);
    const std::int64_t chunk = a.optional_size("chunk_size").value_or(100'000'000);
    if (chunk <= 0) a.fail("chunk_size", "must be > 0");
    const MemoryLimits memory_limits = read_memory_limits(a, "the application's");
    app.memory_max = memory_limits.max;
    app.memory_high = memory_limits.high;
    const auto tasks = a.tables("tasks");
    if (tasks.empty()) a.fail_table("an application needs at least one [[" + a.path() + ".tasks]]");
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      task_origins.push_back({tasks[t], a.child_path("tasks", t), &file});
      app.tasks.push_back(read_task(*tasks[t], a.child_path("tasks", t), t, chunk, file, false));
    }
    a.finish();
    s.apps.push_back(std::move(app));
  }

  if (const toml::table* w = s.workflows.empty() ? r.optional_table("workflow") : nullptr) {
    TomlReader wr(*w, "workflow", file);
    origins.workflows.push_back({w, "workflow", &file});
    std::vector<Origin>& task_origins = origins.workflow_tasks.emplace_back();
    WorkflowSpec workflow;
    workflow.name = wr.name("name", "workflow");
    if (wr.has("hosts")) {
      workflow.hosts = wr.names("hosts");
      if (workflow.hosts.empty()) wr.fail("hosts", "at least one host");
      if (wr.has("host")) wr.fail("host", "give either host or hosts");
    } else {
      workflow.hosts = {wr.name("host", s.hosts.front().name)};
    }
    for (const std::string& h : workflow.hosts) {
      if (std::none_of(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& c) { return c.name == h; })) {
        wr.fail(wr.has("hosts") ? "hosts" : "host", fmt::format("no host named '{}'", h));
      }
    }
    const std::int64_t chunk = wr.optional_size("chunk_size").value_or(100'000'000);
    if (chunk <= 0) wr.fail("chunk_size", "must be > 0");
    const MemoryLimits memory_limits = read_memory_limits(wr, "each task's");
    const auto tasks = wr.tables("tasks");
    if (tasks.empty()) wr.fail_table("a workflow needs at least one [[workflow.tasks]]");
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      task_origins.push_back({tasks[t], wr.child_path("tasks", t), &file});
      workflow.tasks.push_back(read_task(*tasks[t], wr.child_path("tasks", t), t, chunk, file, true, memory_limits));
    }
    check_workflow_acyclic(workflow, origins.workflows.back(), task_origins);
    wr.finish();
    s.workflows.push_back(std::move(workflow));
  }
  if (platform_only) {
    if (simgrid) {
      const std::size_t more = scenario::add_all_simgrid_routes(*simgrid, kMostShownRoutes, s);
      if (more > 0) s.warnings.push_back(fmt::format("{}: {} more routes not shown (the first {} are)", platform_file, more, kMostShownRoutes));
      scenario::add_link_warnings(*simgrid, s);
    }
    r.finish();
    return s;
  }
  if (s.apps.empty() && s.workflows.empty()) {
    r.fail_table("no workload: add [pipelines], [[apps]] or [workflow] (or workflow = \"x.json\", a WfFormat file)");
  }
  r.finish();
  if (simgrid) keep_what_the_run_uses(*simgrid, from_xml, s, origins);

  // References: every file a task names exists on the task's host; files fit their disks.
  std::map<std::string, const FileSpec*> by_name;
  std::unordered_map<std::string_view, const HostConfig*> host_by_name;
  for (const HostConfig& h : s.hosts) host_by_name.emplace(h.name, &h);
  for (std::size_t i = 0; i < s.files.size(); ++i) {
    const FileSpec& f = s.files[i];
    if (!by_name.emplace(f.name, &f).second) origins.file(i).fail("name", fmt::format("two files named '{}'", f.name));
    const HostConfig& h = *host_by_name.at(f.host);
    const auto d = std::find_if(h.disks.begin(), h.disks.end(), [&](const DiskSpec& x) { return x.name == f.disk; });
    if (d == h.disks.end()) origins.file(i).fail("disk", fmt::format("file '{}': host '{}' has no disk '{}'", f.name, h.name, f.disk));
    if (d->capacity > 0 && f.size > d->capacity) {
      origins.file(i).fail(i < origins.files.size() ? "size" : "file_size",
                           fmt::format("file '{}' ({}) does not fit on disk '{}' ({})", f.name, units::format_size(f.size), d->name,
                                       units::format_size(d->capacity)));
    }
  }
  check_disk_space(s, origins);
  // Every host a task may run on reaches its files, over a route that fits in a flow. Each pair
  // of hosts is looked at once: a workflow's tasks may run on every host of a cluster.
  const scenario::RouteIndex routes(s);
  std::set<std::pair<std::string, std::string>> reachable;
  // `where`: the file the tasks were read from, named in messages (a workflow file's own).
  const auto check_reach = [&](const std::string& where, const std::string& owner, const std::string& task, const std::string& file_name,
                               const std::string& host, const std::string& server) {
    if (server == host || !reachable.emplace(host, server).second) return;
    const std::vector<const LinkSpec*>& route = routes.between(host, server);
    if (route.empty()) {
      throw ConfigError(fmt::format("{}: {}, task '{}': file '{}' is on host '{}', and no link or route joins it to '{}'", where, owner,
                                    task, file_name, server, host));
    }
    // A transfer is one flow through its route's shared links, the two memories and a disk
    // (devices.hpp): kMaxResourcesPerFlow in all.
    const auto shared = std::count_if(route.begin(), route.end(), [](const LinkSpec* l) { return l->sharing == LinkSharing::Shared; });
    if (static_cast<std::size_t>(shared) + 2 > kMaxResourcesPerFlow) {
      throw ConfigError(fmt::format("{}: {}, task '{}': the route from '{}' to '{}' crosses {} shared links; pcsim models routes of at most {}",
                                    where, owner, task, host, server, shared, kMaxResourcesPerFlow - 2));
    }
  };
  std::set<std::string> host_names;
  for (const HostConfig& h : s.hosts) host_names.insert(h.name);
  auto check_tasks = [&](const std::string& where, const std::string& owner, const std::vector<std::string>& hosts,
                         const std::vector<TaskSpec>& tasks) {
    for (const std::string& host : hosts) {
      if (host_names.count(host) == 0) throw ConfigError(fmt::format("{}: {}: no host named '{}'", where, owner, host));
    }
    // The hosts storing the files of the tasks that may run on any of `hosts`: (task, file) first
    // needing each, checked against every such host after.
    std::map<std::string, std::pair<const std::string*, const std::string*>> servers;
    for (const TaskSpec& t : tasks) {
      if (!t.host.empty() && host_names.count(t.host) == 0) {
        throw ConfigError(fmt::format("{}: {}, task '{}': no host named '{}'", where, owner, t.name, t.host));
      }
      for (const auto* list : {&t.reads, &t.writes, &t.deletes}) {
        for (const std::string& name : *list) {
          auto it = by_name.find(name);
          if (it == by_name.end()) throw ConfigError(fmt::format("{}: {}, task '{}': unknown file '{}'", where, owner, t.name, name));
          const std::string& server = it->second->host;
          if (!t.host.empty()) check_reach(where, owner, t.name, name, t.host, server);
          else servers.try_emplace(server, &t.name, &it->first);
        }
      }
    }
    for (const auto& [server, first] : servers) {
      for (const std::string& host : hosts) check_reach(where, owner, *first.first, *first.second, host, server);
    }
  };
  for (const AppSpec& a : s.apps) check_tasks(file, "application '" + a.name + "'", {a.host}, a.tasks);
  for (const WorkflowSpec& w : s.workflows) check_tasks(w.source.empty() ? file : w.source, "workflow '" + w.name + "'", w.hosts, w.tasks);
  // A workflow task needing more cores than any host it may run on has would wait for ever.
  for (std::size_t w = 0; w < s.workflows.size(); ++w) {
    const WorkflowSpec& flow = s.workflows[w];
    int most = 0;
    for (const std::string& h : flow.hosts) most = std::max(most, host_by_name.at(h)->cores);
    for (std::size_t t = 0; t < flow.tasks.size(); ++t) {
      const TaskSpec& task = flow.tasks[t];
      const int cores = task.host.empty() ? most : host_by_name.at(task.host)->cores;
      if (task.cores <= cores) continue;
      const std::string message = fmt::format("needs {} cores, more than {} has ({})", task.cores,
                                              task.host.empty() ? "any of its workflow's hosts" : fmt::format("its host '{}'", task.host), cores);
      // A workflow file's task is named by its place.
      if (flow.source.empty()) origins.workflow_tasks[w][t].fail("cores", fmt::format("task '{}': {}", task.name, message));
      origins.workflow_tasks[w][t].fail_table(message);
    }
  }
  scenario::check_reads_of_deleted_files(s, origins);
  scenario::check_limits(s, origins, limits);
  return s;
}

}  // namespace

Scenario parse_scenario(const std::string& toml_text, const std::string& source_name, const Overrides& overrides,
                        const std::string& profile_override, const ScenarioLimits& limits) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}:{}:{}: {}", source_name, e.source().begin.line, e.source().begin.column, e.description()));
  }
  return scenario::resolve_document(std::move(root), source_name, overrides, profile_override, limits);
}

Scenario scenario::resolve_document(toml::table root, const std::string& source_name, const Overrides& overrides,
                                    const std::string& profile_override, const ScenarioLimits& limits) {
  // A key of the platform's hosts, links or routes, in a scenario that takes them from a
  // platform file, changes that file's table (as read for this run only).
  Overrides of_platform;
  for (const auto& [key, value] : overrides) {
    const std::string first = key.substr(0, key.find('.'));
    const bool platform_part = first == "hosts" || first == "links" || first == "routes";
    if (platform_part && key != first && !root.contains(first) && root.contains("platform")) of_platform.emplace_back(key, value);
    else apply_override(root, key, value, source_name);
  }
  return resolve(root, source_name, profile_override, limits, false, of_platform);
}

Scenario load_platform(const std::string& path, const std::string& profile_override) {
  toml::table root;
  root.insert("platform", std::filesystem::path(path).filename().string());
  return resolve(root, path, profile_override, ScenarioLimits{}, true);
}

Scenario load_scenario(const std::string& path, const Overrides& overrides, const std::string& profile_override,
                       const ScenarioLimits& limits) {
  return parse_scenario(scenario::read_text_file(path, "scenario file"), path, overrides, profile_override, limits);
}

}  // namespace pagecache
