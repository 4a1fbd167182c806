#pragma once
// Platform: what a run's scenario builds before anything runs: its hosts with their disks, the
// links and routes between hosts, and its files placed on their hosts' disks. A host reaches
// a file of another host through the route that joins them, as through an NFS mount.

#include <pagecache/devices.hpp>
#include <pagecache/fair_share.hpp>
#include <pagecache/host.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/simulator.hpp>

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pagecache::workload {

/// A file where it is stored (its name is its host's: Host::file_name).
struct PlacedFile {
  Host* host;
  FileRef ref;
};

/// A file set's files: Platform::files() from `first`, `count` of them, in the set's order.
struct PlacedFileSet {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

/// The scenario's files by name (views of the scenario's names): their index in Platform::files().
using FileIndex = std::unordered_map<std::string_view, std::uint32_t>;

class Platform {
 public:
  /// Builds the hosts, links and routes of `scenario` and places its files, each indexed in
  /// `files` by its name. `sim` and `share` must outlive the platform.
  Platform(Simulator& sim, FairShare& share, const Scenario& scenario, FileIndex& files);
  Platform(const Platform&) = delete;
  Platform& operator=(const Platform&) = delete;

  /// Scenarios built in code skip the loader's checks: what the run relies on is checked here.
  /// `kind` and `owner` name what asks for the host (e.g. file 'a'), for the error only.
  Host& host_named(const std::string& name, const char* kind, const std::string& owner) const;
  /// A host the scenario has, and its cores.
  Host& host(const std::string& name) const { return *hosts_.at(name); }
  int cores(const std::string& host) const { return cores_.at(host); }

  /// The hosts and their names, in the scenario's order.
  const std::vector<Host*>& hosts() const noexcept { return host_list_; }
  const std::vector<std::string>& host_names() const noexcept { return host_order_; }
  /// The scenario's files, in its order, then the files of its file sets, set by set.
  const std::vector<PlacedFile>& files() const noexcept { return file_order_; }
  /// The scenario's file sets, in its order.
  const std::vector<PlacedFileSet>& file_sets() const noexcept { return sets_; }

  /// The file as seen from `client`: its own, or the server's through the route between them
  /// (registered once per host and file, when first used).
  FileRef file_on(Host& client, const PlacedFile& stored) {
    if (stored.host == &client) return stored.ref;
    return remote_file(client, stored);
  }

 private:
  using Disks = std::map<std::string, std::map<std::string, DiskRef>>;  // per host, by name

  void add_host(Simulator& sim, FairShare& share, const HostConfig& config, Disks& disks);
  void add_links(FairShare& share, const Scenario& scenario);
  void place_files(const std::vector<FileSpec>& specs, const Disks& disks, FileIndex& files);
  void place_file_sets(const std::vector<FileSetSpec>& specs, const Disks& disks);
  FileRef remote_file(Host& client, const PlacedFile& stored);

  std::map<std::string, std::unique_ptr<Host>> hosts_;
  std::map<std::string, int> cores_;
  std::vector<std::string> host_order_;
  std::vector<Host*> host_list_;  // in host_order_
  std::deque<Link> links_storage_;
  std::deque<Route> routes_storage_;
  std::map<std::pair<std::string, std::string>, const Route*> routes_;
  std::vector<PlacedFile> file_order_;  // the scenario's files, in its order, then its sets'
  std::vector<PlacedFileSet> sets_;
  std::map<std::tuple<const Host*, const Host*, std::uint32_t>, FileRef> remote_files_;  // (client, server, server's file)
};

}  // namespace pagecache::workload
