#include "scenario/simgrid_import.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include "formats/simgrid/xml/units.hpp"
#include "scenario/toml_reader.hpp"
#include "text/printable.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::scenario {

using namespace formats::simgrid;  // the SimGrid reader's platform

namespace {

const std::string* prop(const std::vector<std::pair<std::string, std::string>>& props, std::string_view key) {
  for (const auto& [k, v] : props) {
    if (k == key) return &v;
  }
  return nullptr;
}

std::string where(const SgPlatform& p, int line, const std::string& what) { return fmt::format("{}:{}: {}", p.file, line, what); }

// A size prop as whole bytes: SimGrid reads it as a double of bytes.
std::int64_t size_prop(const SgPlatform& p, int line, const std::string& what, const std::string& value) {
  double bytes = 0.0;
  try {
    bytes = parse_sg_size(value);
  } catch (const ConfigError& e) {
    throw ConfigError(fmt::format("{}: {}", where(p, line, what), e.what()));
  }
  if (!(bytes >= 1.0) || bytes > static_cast<double>(units::kMaxBytes)) {
    throw ConfigError(fmt::format("{}: '{}' is not a size pcsim takes (1 B to 1 EiB)", where(p, line, what), value));
  }
  return static_cast<std::int64_t>(std::llround(bytes));
}

// A bandwidth within what pcsim takes. SimGrid files give "infinite" links as huge ones
// (WRENCH-cache's loopback: 1000 EBps): above 1 PB/s a link limits nothing a run can do,
// and is taken as 1 PB/s.
double bandwidth(SgPlatform const& p, int line, const std::string& what, double value, Scenario& s, bool warn = true) {
  if (!(value >= units::kMinBandwidth) || !std::isfinite(value)) {
    throw ConfigError(fmt::format("{}: bandwidth {} B/s is below the 1 B/s pcsim takes", where(p, line, what), value));
  }
  if (value > units::kMaxBandwidth) {
    if (warn) s.warnings.push_back(fmt::format("{}: {:g} B/s taken as 1 PB/s, the most pcsim models", where(p, line, what), value));
    return units::kMaxBandwidth;
  }
  return value;
}

// An id pcsim can use as a name (those of scenario files: printable UTF-8, no leading formula
// character); SimGrid's XML takes any text, and pugixml does not check its encoding.
void check_name(const SgPlatform& p, int line, const std::string& what, const std::string& id) {
  if (const std::string problem = formats::name_problem(id); !problem.empty()) throw ConfigError(fmt::format("{}: id: {}", where(p, line, what), problem));
}

}  // namespace

void add_link_warnings(const SgPlatform& p, Scenario& s) {
  for (const LinkSpec& link : s.links) {
    const SgLink* sg = p.find_link(link.name);
    if (sg != nullptr && sg->bandwidth > units::kMaxBandwidth) {
      s.warnings.push_back(fmt::format("{}: {:g} B/s taken as 1 PB/s, the most pcsim models",
                                       where(p, sg->line, fmt::format("link '{}', bandwidth", sg->id)), sg->bandwidth));
    }
  }
}

bool is_memory_disk(const SgDisk& disk) {
  const std::string* mount = prop(disk.props, "mount");
  return disk.id == "memory" || (mount != nullptr && *mount == "/memory");
}

void add_simgrid_platform(const SgPlatform& p, Scenario& s, Origins& origins) {
  s.warnings.insert(s.warnings.end(), p.warnings.begin(), p.warnings.end());
  for (const SgHost& sg : p.hosts) {
    const std::string what = fmt::format("host '{}'", text::printable(sg.id));
    check_name(p, sg.line, "host", sg.id);
    HostConfig h;
    h.name = sg.id;
    h.cores = sg.cores;
    h.cache = settings_for(s.profile);
    if (const std::string* ram = prop(sg.props, "ram")) h.memory = size_prop(p, sg.line, what + ", prop 'ram'", *ram);
    for (const auto& [key, value] : sg.props) {
      if (key != "ram" && key.rfind("wattage", 0) != 0) {
        s.warnings.push_back(fmt::format("{}: prop '{}' is not modelled by pcsim; ignored", where(p, sg.line, what), key));
      }
    }
    std::vector<Origin>& disk_origins = origins.disks.emplace_back();
    for (const SgDisk& disk : sg.disks) {
      const std::string disk_what = fmt::format("{}, disk '{}'", what, text::printable(disk.id));
      check_name(p, disk.line, what + ", disk", disk.id);
      const std::string* size = prop(disk.props, "size");
      for (const auto& [key, value] : disk.props) {
        if (key != "size" && key != "mount") {
          s.warnings.push_back(fmt::format("{}: prop '{}' is not modelled by pcsim; ignored", where(p, disk.line, disk_what), key));
        }
      }
      if (is_memory_disk(disk)) {
        // WRENCH-cache's memory: one device, so one channel for all copies (read and write).
        const double read = bandwidth(p, disk.line, disk_what + ", read_bw", disk.read_bw, s);
        const double write = bandwidth(p, disk.line, disk_what + ", write_bw", disk.write_bw, s);
        h.memory_bandwidth = {read, write, read, write, 0.0};
        if (h.memory == 0 && size != nullptr) h.memory = size_prop(p, disk.line, disk_what + ", prop 'size'", *size);
        continue;
      }
      DiskSpec d;
      d.name = disk.id;
      d.read_bw = bandwidth(p, disk.line, disk_what + ", read_bw", disk.read_bw, s);
      d.write_bw = bandwidth(p, disk.line, disk_what + ", write_bw", disk.write_bw, s);
      if (size != nullptr) d.capacity = size_prop(p, disk.line, disk_what + ", prop 'size'", *size);
      h.disks.push_back(std::move(d));
      disk_origins.push_back(Origin::elsewhere(where(p, disk.line, disk_what)));
    }
    origins.hosts.push_back(Origin::elsewhere(where(p, sg.line, what)));
    origins.page_caches.push_back(origins.hosts.back());
    s.hosts.push_back(std::move(h));
  }
  for (const SgLink& sg : p.links) {
    LinkSpec link;
    link.name = sg.id;
    const std::string what = fmt::format("link '{}'", text::printable(sg.id));
    check_name(p, sg.line, "link", sg.id);
    // Said only of the links a run keeps (add_link_warnings): WRENCH-cache's loopbacks are
    // 1000 EBps and a run rarely crosses them.
    link.bandwidth = bandwidth(p, sg.line, what + ", bandwidth", sg.bandwidth, s, false);
    if (!(sg.latency >= 0.0) || sg.latency > units::kMaxSeconds) {
      throw ConfigError(fmt::format("{}: latency {} s is not one pcsim takes (0 to 10^9 s)", where(p, sg.line, what), sg.latency));
    }
    link.latency = sg.latency;
    link.sharing = sg.sharing == formats::simgrid::LinkSharing::Fatpipe ? pagecache::LinkSharing::Fatpipe : pagecache::LinkSharing::Shared;
    origins.links.push_back(Origin::elsewhere(where(p, sg.line, what)));
    s.links.push_back(std::move(link));
  }
}

void add_simgrid_routes(const SgPlatform& p, const std::set<std::pair<std::string, std::string>>& pairs, Scenario& s) {
  std::set<std::pair<std::string, std::string>> added;
  for (const auto& [a, b] : pairs) {
    if (a == b || added.count({b, a}) != 0 || !added.emplace(a, b).second) continue;
    // The route from the host that runs tasks to the one that stores files. pcsim's routes
    // serve both directions: for a SPLITDUPLEX link, the halves of this direction.
    const SgRoute* route = p.find_route(a, b);
    if (route == nullptr) continue;
    s.routes.push_back({a, b, route->links});
  }
}

void add_all_simgrid_routes(const SgPlatform& p, Scenario& s) {
  std::set<std::pair<std::string, std::string>> added;
  p.for_each_route([&](const SgRoute& route) {
    if (route.src == route.dst) return;  // a loopback: pcsim reads a host's own files without the network
    // pcsim's routes serve both ways: of a routed platform's two ways, the first listed.
    if (p.is_routed() && (added.count({route.dst, route.src}) != 0 || !added.emplace(route.src, route.dst).second)) return;
    s.routes.push_back({route.src, route.dst, route.links});
  });
}

std::size_t add_example_simgrid_routes(const SgPlatform& p, std::size_t most, Scenario& s) {
  std::size_t added = 0;
  for (const SgRoute& route : p.first_routes(2 * most + 1)) {
    if (route.src == route.dst || added == most) continue;
    s.routes.push_back({route.src, route.dst, route.links});
    ++added;
  }
  return added;
}

}  // namespace pagecache::scenario
