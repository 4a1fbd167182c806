// Where a scenario's platform comes from: a platform file (TOML, or SimGrid XML with
// WRENCH-cache's conventions) and the scenario's own [[hosts]], [[links]] and [[routes]]; and
// what a run keeps of a SimGrid platform once its workload is known.

#include "scenario/loader_sections.hpp"

#include <pagecache/error.hpp>

#include "scenario/simgrid_import.hpp"
#include "formats/common/text_file.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace pagecache::scenario {

using namespace formats::simgrid;  // the SimGrid reader's platform

namespace {

// `pcsim show` of a platform alone lists every route of a platform of at most this many hosts
// and routes, and else a summary with a few routes (a cluster of N hosts has N (N - 1) / 2).
constexpr std::size_t kWholeHosts = 100;
constexpr std::size_t kWholeRoutes = 5'050;  // SimGrid's cluster of 100 nodes (cluster_backbone.xml), whole
constexpr std::size_t kExampleRoutes = 10;

// A SimGrid platform: named .xml, or XML inside (a byte-order mark and spaces aside).
bool is_xml_file(const std::string& path, const std::string& text) {
  if (std::filesystem::path(path).extension() == ".xml") return true;
  std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n')) ++i;
  return i < text.size() && text[i] == '<';
}

// platform = "file.toml" or "file.xml" (SimGrid), or one per profile:
// platform = { paper = "a.toml", linux = "b.toml" }
std::string platform_path(TomlReader& r, const toml::node& platform, Profile profile) {
  if (platform.is_string()) return *platform.value<std::string>();
  if (const toml::table* per_profile = platform.as_table()) {
    const toml::node* chosen = per_profile->get(to_string(profile));
    if (chosen == nullptr || !chosen->is_string()) r.fail("platform", fmt::format("no platform file for profile '{}'", to_string(profile)));
    return *chosen->value<std::string>();
  }
  r.fail("platform", "expected a file name, or a table of file names per profile");
}

void read_xml_platform(const std::string& text, const Overrides& platform_overrides, Scenario& s, Origins& origins, PlatformFile& platform) {
  if (!platform_overrides.empty()) {
    throw ConfigError(fmt::format("--set {}: the hosts, links and routes come from a SimGrid platform file ({}): amend a host with a "
                                  "[[hosts]] table naming it", platform_overrides.front().first, platform.file));
  }
  platform.simgrid = read_simgrid_platform(text, platform.file);
  add_simgrid_platform(*platform.simgrid, s, origins);
  for (std::size_t h = 0; h < s.hosts.size(); ++h) {
    platform.from_xml.insert(h);
    // The speed, read by a workflow file's compute = "speed" alone.
    if (const SgHost* host = platform.simgrid->find_host(s.hosts[h].name)) s.hosts[h].speed = host->speed;
  }
}

void read_toml_platform(const std::string& text, const Overrides& platform_overrides, const ScenarioLimits& limits, Scenario& s, Origins& origins,
                        PlatformFile& platform) {
  try {
    platform.root = toml::parse(text, platform.file);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}:{}:{}: {}", platform.file, e.source().begin.line, e.source().begin.column, e.description()),
                      InputPlace{.file = platform.file, .line = static_cast<int>(e.source().begin.line), .key = {}});
  }
  for (const auto& [key, value] : platform_overrides) apply_override(platform.root, key, value, platform.file);
  TomlReader p(platform.root, "", platform.file);
  p.string("title", "");
  std::set<std::size_t> amendable;  // none: a TOML platform's hosts are the file's own
  read_platform(p, s, platform.file, limits, origins, amendable);
  p.finish();
}

}  // namespace

void read_platform_file(TomlReader& r, const std::string& file, const Overrides& platform_overrides, const ScenarioLimits& limits, Scenario& s, Origins& origins,
                        PlatformFile& platform) {
  const toml::node* node = r.raw("platform");
  if (node == nullptr) return;
  platform.file = relative_path(file, platform_path(r, *node, s.profile));
  std::string text;
  try {
    text = formats::read_text_file(platform.file, "platform file");
  } catch (const ConfigError& e) {
    r.fail("platform", e.what());
  }
  if (is_xml_file(platform.file, text)) {
    read_xml_platform(text, platform_overrides, s, origins, platform);
  } else {
    read_toml_platform(text, platform_overrides, limits, s, origins, platform);
  }
}

void read_platform(TomlReader& r, Scenario& s, const std::string& file, const ScenarioLimits& limits, Origins& origins, std::set<std::size_t>& amendable) {
  read_hosts(r, s, file, limits, origins, amendable);
  read_network(r, s, file, origins);
}

namespace {

// A summary keeps the first hosts and links, and those of the routes it shows.
void keep_examples(Scenario& s) {
  std::set<std::string> hosts, links;
  for (const RouteSpec& r : s.routes) {
    hosts.insert(r.host_a), hosts.insert(r.host_b);
    links.insert(r.links.begin(), r.links.end());
  }
  std::size_t first = 0;
  std::erase_if(s.hosts, [&](const HostConfig& h) { return first++ >= kExampleRoutes && hosts.count(h.name) == 0; });
  first = 0;
  std::erase_if(s.links, [&](const LinkSpec& l) { return first++ >= kExampleRoutes && links.count(l.name) == 0; });
}

}  // namespace

void add_shown_routes(const PlatformFile& platform, Scenario& s) {
  if (!platform.simgrid) return;
  const SgPlatform& p = *platform.simgrid;
  // Counted without listing them; a routed platform's only when it is small enough to list.
  const std::size_t routes = p.route_count(kWholeHosts);
  if (p.hosts.size() <= kWholeHosts && routes <= kWholeRoutes) {
    add_all_simgrid_routes(p, s);
  } else {
    const std::size_t shown = add_example_simgrid_routes(p, kExampleRoutes, s);
    const std::string count = routes > 0 ? fmt::format("{} routes", routes) : fmt::format("routes between {} pairs of hosts", p.hosts.size() * (p.hosts.size() - 1) / 2);
    s.warnings.push_back(fmt::format("{}: a summary: {} hosts, {} links, {}; shown: the first {} hosts and routes, and the hosts and links "
                                     "those routes cross (`pcsim run` finds the routes it needs)",
                                     platform.file, p.hosts.size(), p.links.size(), count, std::max(shown, kExampleRoutes)));
    keep_examples(s);
  }
  add_link_warnings(p, s);
}

// A run on a SimGrid platform keeps what it uses: the hosts that run tasks or store files, the
// routes between them and the links those cross (a cluster's N^2 routes are never listed). The
// hosts it keeps must say what the model needs of them.
void keep_what_the_run_uses(const SgPlatform& platform, const std::set<std::size_t>& from_xml, Scenario& s, Origins& origins) {
  std::set<std::string> runs, stores;
  for (const AppSpec& a : s.apps) runs.insert(a.host);
  for (const WorkflowSpec& w : s.workflows) {
    runs.insert(w.hosts.begin(), w.hosts.end());
    for (const TaskSpec& t : w.tasks) {
      if (!t.host.empty()) runs.insert(t.host);
    }
  }
  for (const FileSpec& f : s.files) stores.insert(f.host);
  for (const FileSetSpec& f : s.file_sets) stores.insert(f.host);
  std::set<std::pair<std::string, std::string>> pairs;
  for (const std::string& a : runs) {
    for (const std::string& b : stores) pairs.emplace(a, b);
  }
  const std::size_t routes_before = s.routes.size();
  add_simgrid_routes(platform, pairs, s);
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
  add_link_warnings(platform, s);

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

}  // namespace pagecache::scenario
