// The hosts of a scenario or platform file: [[hosts]] (each with its memory, memory bandwidths,
// page cache and [[hosts.disks]], or a group of hosts alike), [host_defaults] for the hosts of a
// SimGrid platform, and [start.memory_in_use].

#include "scenario/limits.hpp"
#include "scenario/loader_sections.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/error.hpp>

#include "formats/simgrid/xml/units.hpp"
#include "storage/readahead.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_set>

namespace pagecache::scenario {

namespace {

// A policy's parameter as its kind is written: true/false, an integer, a size ("64 KiB"), a
// number for a ratio; its bounds are CacheSettings::set's to check.
std::optional<ParameterValue> read_parameter(TomlReader& r, const PolicyParameter& p) {
  const std::string key(p.key);
  switch (p.kind) {
    case ParameterKind::Switch:
      if (const auto v = r.optional_bool(key)) return *v;
      return std::nullopt;
    case ParameterKind::Integer:
      if (const auto v = r.optional_integer(key)) return *v;
      return std::nullopt;
    case ParameterKind::Size:
      if (const auto v = r.optional_size(key)) return *v;
      return std::nullopt;
    case ParameterKind::Ratio:
      if (const auto v = r.optional_number(key)) return *v;
      return std::nullopt;
  }
  return std::nullopt;
}

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
  // The host model's switches, whatever the policy.
  for (const PolicyParameter& parameter : host_model_switches()) {
    if (const auto v = r.optional_bool(std::string(parameter.key))) s.set(parameter.key, *v);
  }
  // A policy's parameters: setting one chooses that policy, the others keeping the profile's
  // values (CacheSettings::set: under the paper profile, WRENCH-cache's).
  const PolicyParameter* first_set = nullptr;  // and its policy's name
  std::string_view first_owner;
  for (const PolicyDeclaration& owner : cache_policies()) {
    for (const PolicyParameter& parameter : owner.parameters) {
      const std::optional<ParameterValue> v = read_parameter(r, parameter);
      if (!v) continue;
      if (policy && *policy != owner.name) {
        r.fail(std::string(parameter.key), fmt::format("a parameter of the {} policy, and this host's policy is '{}'", owner.name, *policy));
      }
      if (first_set != nullptr && first_owner != owner.name) {
        r.fail(std::string(parameter.key), fmt::format("a parameter of the {} policy, and {} (also set) is one of the {} policy's", owner.name,
                                                       first_set->key, first_owner));
      }
      first_set = &parameter;
      first_owner = owner.name;
      // Set alone, it chooses its policy (the profile's, or a preset of it, keeps its values).
      if (const PolicyDeclaration* own = find_cache_policy(s.policy); own != nullptr && own->parameter(parameter.key) == nullptr &&
                                                                        own->preset_of != owner.name) {
        s.policy = std::string(owner.name);
        s.parameters.clear();
      }
      try {
        s.set(parameter.key, *v);
      } catch (const ConfigError& e) {
        r.fail(std::string(parameter.key), e.what());  // out of its bounds
      }
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
  h.request_time = r.optional_duration("request_time").value_or(h.request_time);
  if (!(h.request_time >= 0.0 && h.request_time <= 1.0)) r.fail("request_time", "must be >= 0 s and at most 1 s (a system call's time)");
}

// [hosts.numa] (docs/model.md §6.20): absent, one node. A table amending a host keeps what it
// does not give. Each ratio scales some of the host's memory rates (`bw`, read before): the
// rates it makes must be rates pcsim takes, at least units::kMinBandwidth.
void read_numa(const toml::table* table, const TomlReader& parent, NumaSpec& numa, const MemoryBandwidth& bw, const std::string& file) {
  if (table == nullptr) return;
  TomlReader r(*table, parent.child_path("numa"), file);
  numa.nodes = static_cast<int>(r.optional_integer("nodes", 1, 2).value_or(numa.nodes));
  // The slowest local rate each ratio scales (0: none given), and what it is.
  const auto slowest = [](std::initializer_list<double> rates) {
    double low = 0.0;
    for (const double rate : rates)
      if (rate > 0.0 && (low == 0.0 || rate < low)) low = rate;
    return low;
  };
  const struct {
    const char* key;
    double* ratio;
    double local;
    const char* what;
  } ratios[] = {
      {"remote_copy_ratio", &numa.remote.copy, slowest({bw.read, bw.write}), "a thread's copy"},
      {"remote_first_touch_ratio", &numa.remote.first_touch, slowest({bw.first_touch}), "a thread's first touch"},
      {"remote_aggregate_ratio", &numa.remote.aggregate, slowest({bw.aggregate_read, bw.aggregate_write}) / numa.nodes, "a node's threads together"},
  };
  for (const auto& [key, ratio, local, what] : ratios) {
    *ratio = r.optional_number(key).value_or(*ratio);
    if (!(*ratio > 0.0 && *ratio <= 10.0)) {
      r.fail(key, fmt::format("must be > 0 and at most 10 (a remote rate over the local one), got {:.6g}", *ratio));
    }
    if (local > 0.0 && *ratio * local < units::kMinBandwidth) {
      r.fail(key, fmt::format("{:.6g} makes {} with the other node's memory {:.3g} B/s, below the 1 B/s pcsim takes (the local rate is "
                              "{:.6g} B/s)",
                              *ratio, what, *ratio * local, local));
    }
  }
  r.finish();
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

// The [[hosts.disks]] tables of host `h` (`fresh`: not one a platform file gave, which then
// needs a disk): a disk of a known name is amended, another added. Their origins, in the host's
// order, in `disk_origins`.
void read_disks(TomlReader& r, const std::string& file, bool fresh, HostConfig& h, std::vector<Origin>& disk_origins) {
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
  h.speed = read_speed(r, "speed").value_or(h.speed);
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
  read_numa(r.optional_table("numa"), r, h.numa, h.memory_bandwidth, file);
  read_disks(r, file, fresh, h, disk_origins);
  if (count != nullptr) {
    *count = r.optional_integer("count", 1, kMaxGroupHosts).value_or(0);
  } else if (r.has("count")) {
    r.fail("count", "a host amending a platform file's is one host: give count where the hosts are first described");
  }
  r.finish();
  return h;
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

}  // namespace

void read_hosts(TomlReader& r, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins, std::set<std::size_t>& amendable) {
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
    // The run's limit on hosts, on the declared count, before a member is made.
    if (static_cast<double>(s.hosts.size()) + static_cast<double>(count) > static_cast<double>(limits.max_hosts)) {
      TomlReader(*hosts[i], r.child_path("hosts", i), file)
          .fail("count", fmt::format("{} hosts, more than the {} a run may have{}", s.hosts.size() + static_cast<std::size_t>(count), limits.max_hosts,
                                     limits_hint(limits)));
    }
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
}

void read_host_defaults(TomlReader& r, const std::string& file, const std::set<std::size_t>& from_xml, Scenario& s, Origins& origins) {
  if (const toml::table* defaults = r.optional_table("host_defaults")) {
    if (from_xml.empty()) r.fail("host_defaults", "fills in what a SimGrid platform file does not say; this scenario has none");
    apply_host_defaults(*defaults, file, from_xml, s, origins);
  }
}

// [start.memory_in_use]: host name -> memory in use when this run starts (what a measured
// run began with, e.g. tmpfs contents), replacing the platform's figure for that host.
void read_start(TomlReader& r, const std::string& file, Scenario& s) {
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
}

std::optional<double> read_speed(TomlReader& r, const std::string& key) {
  const toml::node* node = r.raw(key);
  if (node == nullptr) return std::nullopt;
  double speed = 0;
  if (node->is_number()) {
    speed = *node->value<double>();
  } else if (node->is_string()) {
    try {
      speed = formats::simgrid::parse_sg_speed(*node->value<std::string>());
    } catch (const ConfigError& e) {
      r.fail(key, e.what());
    }
  } else {
    r.fail(key, "expected a speed in flop/s: a number, or a string in SimGrid's units such as \"1.2Gf\"");
  }
  if (!(speed > 0.0) || !std::isfinite(speed)) r.fail(key, fmt::format("must be > 0 flop/s, got {}", speed));
  return speed;
}

}  // namespace pagecache::scenario
