#include "workload/platform.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

namespace pagecache::workload {

Platform::Platform(Simulator& sim, FairShare& share, const Scenario& scenario, FileIndex& files) {
  Disks disks;
  for (const HostConfig& config : scenario.hosts) add_host(sim, share, config, disks);
  add_links(share, scenario);
  place_files(scenario.files, disks, files);
  place_file_sets(scenario.file_sets, disks);
}

void Platform::add_host(Simulator& sim, FairShare& share, const HostConfig& config, Disks& disks) {
  auto host = std::make_unique<Host>(sim, share,
                                     HostSpec{config.name, config.cores, config.memory, config.memory_bandwidth, config.cache, config.memory_in_use,
                                              config.page_reporting_delay, config.memory_freed_at_start, config.request_time, config.numa});
  std::map<std::string, DiskRef> named;
  for (const DiskSpec& d : config.disks) {
    named[d.name] = host->add_disk(config.name + ":" + d.name,  // named as the host's cpu and memory are
                                   DiskBandwidth{.read = d.read_bw,
                                                 .write = d.write_bw,
                                                 .aggregate_read = d.aggregate_read_bw,
                                                 .aggregate_write = d.aggregate_write_bw,
                                                 .request_latency = d.request_latency,
                                                 .read_ahead = d.read_ahead,
                                                 .max_request = d.max_request,
                                                 .write_cache = d.write_cache,
                                                 .sustained_write = d.sustained_write_bw},
                                   d.capacity);
  }
  disks[config.name] = std::move(named);
  hosts_[config.name] = std::move(host);
  cores_[config.name] = config.cores;
  host_order_.push_back(config.name);
  host_list_.push_back(hosts_[config.name].get());
}

void Platform::add_links(FairShare& share, const Scenario& scenario) {
  std::map<std::string, const Link*> links;
  for (const LinkSpec& l : scenario.links) {
    const Link& link = links_storage_.emplace_back(share, l.name, l.bandwidth, l.latency, l.sharing);
    links[l.name] = &link;
    if (!l.host_a.empty()) routes_[{l.host_a, l.host_b}] = &routes_storage_.emplace_back(std::vector<const Link*>{&link});
  }
  for (const RouteSpec& r : scenario.routes) {
    std::vector<const Link*> crossed;
    for (const std::string& name : r.links) {
      const auto it = links.find(name);
      if (it == links.end()) throw ConfigError(fmt::format("route from '{}' to '{}': no link named '{}'", r.host_a, r.host_b, name));
      crossed.push_back(it->second);
    }
    routes_[{r.host_a, r.host_b}] = &routes_storage_.emplace_back(std::move(crossed));
  }
}

void Platform::place_files(const std::vector<FileSpec>& specs, const Disks& disks, FileIndex& files) {
  files.reserve(specs.size());
  file_order_.reserve(specs.size());
  for (const FileSpec& f : specs) {
    Host& host = host_named(f.host, "file", f.name);
    const auto disk = disks.at(f.host).find(f.disk);
    if (disk == disks.at(f.host).end()) throw ConfigError(fmt::format("file '{}': host '{}' has no disk named '{}'", f.name, f.host, f.disk));
    if (!files.try_emplace(f.name, static_cast<std::uint32_t>(file_order_.size())).second) {
      throw ConfigError(fmt::format("two files named '{}'", f.name));
    }
    file_order_.push_back({&host, host.add_file(f.name, f.size, disk->second, f.cached)});
  }
}

// A set's files are its host's files like any other (each read whole through the page cache),
// but have no FileSpec and no entry in the index by name: tasks reach them through their set.
void Platform::place_file_sets(const std::vector<FileSetSpec>& specs, const Disks& disks) {
  std::size_t total = file_order_.size();
  for (const FileSetSpec& set : specs) total += static_cast<std::size_t>(std::max<std::int64_t>(set.count, 0));
  if (total > UINT32_MAX) throw ConfigError(fmt::format("{} files: a run may have at most {}", total, UINT32_MAX));
  file_order_.reserve(total);
  sets_.reserve(specs.size());
  for (const FileSetSpec& set : specs) {
    if (set.count < 1) throw ConfigError(fmt::format("file set '{}': count must be >= 1", set.name));
    Host& host = host_named(set.host, "file set", set.name);
    const auto disk = disks.at(set.host).find(set.disk);
    if (disk == disks.at(set.host).end()) throw ConfigError(fmt::format("file set '{}': host '{}' has no disk named '{}'", set.name, set.host, set.disk));
    sets_.push_back({static_cast<std::uint32_t>(file_order_.size()), static_cast<std::uint32_t>(set.count)});
    for (std::int64_t i = 0; i < set.count; ++i) {
      file_order_.push_back({&host, host.add_file(fmt::format("{}/{}", set.name, i), set.size, disk->second, set.cached)});
    }
  }
}

Host& Platform::host_named(const std::string& name, const char* kind, const std::string& owner) const {
  const auto it = hosts_.find(name);
  if (it == hosts_.end()) throw ConfigError(fmt::format("{} '{}': no host named '{}'", kind, owner, name));
  return *it->second;
}

FileRef Platform::remote_file(Host& client, const PlacedFile& stored) {
  const auto key = std::make_tuple(&client, stored.host, stored.ref.index);
  if (auto it = remote_files_.find(key); it != remote_files_.end()) return it->second;
  const std::string& server = stored.host->name();
  auto route = routes_.find({client.name(), server});
  if (route == routes_.end()) route = routes_.find({server, client.name()});
  if (route == routes_.end()) {
    throw ConfigError(fmt::format("file '{}' is on host '{}', and no route joins it to host '{}'", stored.host->file_name(stored.ref), server,
                                  client.name()));
  }
  const FileRef ref = client.add_remote_file(*stored.host, stored.ref, *route->second);
  remote_files_.emplace(key, ref);
  return ref;
}

}  // namespace pagecache::workload
