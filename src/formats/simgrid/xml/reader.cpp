// read_simgrid_platform: SimGrid platform XML -> SgPlatform, in one pass over the elements in
// document order, so that a route sees only the hosts and links declared before it, as in
// SimGrid (whose parser is a SAX parser building the platform as it reads).

#include "formats/simgrid/xml/reader.hpp"

#include "formats/simgrid/xml/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <iterator>

namespace pagecache::formats::simgrid {

namespace {

// Zones nest by recursion: bounded so that a file of nested zones cannot overflow the stack.
constexpr int kMaxZoneDepth = 64;

constexpr SgRefused kHostTraces[] = {
    {"speed_file", "not supported: a speed profile changes the host's speed over time"},
    {"availability_file", "not supported: a speed profile changes the host's speed over time"},
    {"state_file", "not supported: a state profile turns the host off and on"},
};
constexpr SgRefused kLinkTraces[] = {
    {"bandwidth_file", "not supported: a bandwidth profile changes the link over time"},
    {"latency_file", "not supported: a latency profile changes the link over time"},
    {"state_file", "not supported: a state profile turns the link off and on"},
};

// Host properties of SimGrid's energy plugin: pcsim models no energy.
constexpr std::string_view kEnergyProps[] = {"wattage_per_state", "wattage_off", "wattage_range"};


}  // namespace

SgReader::SgReader(const std::string& text, const std::string& file, const SgLimits& limits)
    : text_(text), limits_(limits), xml_(text, file, platform_.warnings) {
  platform_.file = file;
}

SgPlatform SgReader::read() {
  pugi::xml_document doc;
  // UTF-8 as is: pugixml's offsets, hence our line numbers, are those of the text we hold.
  const pugi::xml_parse_result parsed = doc.load_buffer(text_.data(), text_.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) throw ConfigError(fmt::format("{}:{}: malformed XML: {}", xml_.file(), xml_.line_at(parsed.offset), parsed.description()));
  bool seen = false;
  xml_.for_each_element(doc, [&](const pugi::xml_node& e) {
    if (std::string_view(e.name()) != "platform") xml_.fail(e, "the document's element should be <platform>");
    if (seen) xml_.fail(e, "a second <platform>");
    seen = true;
    platform(e);
  });
  platform_.build_index();
  return std::move(platform_);
}

void SgReader::platform(const pugi::xml_node& e) {
  xml_.check_attributes(e, {"version"});
  const std::string version = xml_.required(e, "version");
  if (version != "4" && version != "4.0" && version != "4.1") {
    xml_.fail_attribute(e, "version", fmt::format("'{}' is not supported (versions 4 and 4.1 are)", sg_shown(version)));
  }
  platform_.version = version == "4.1" ? "4.1" : "4";
  bool top_level = false;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    const std::string_view name = child.name();
    if (name == "config") {
      config(child);
    } else if (name == "prop") {
      SgProps ignored;
      std::unordered_set<std::string> ids;
      prop(child, ignored, ids);
      xml_.warn(child, "ignored: a platform-wide property cannot change pcsim's result");
    } else if (name == "random") {
      xml_.warn(child, "ignored (SimGrid ignores <random> too)");
    } else if (name == "zone" || name == "AS" || name == "cluster") {
      // SimGrid's root zone is set once: a second top-level one is refused there too.
      if (top_level) xml_.fail(child, "a second top-level zone: a platform has one, which holds the others");
      top_level = true;
      if (name == "cluster") {
        cluster(child, kNoZone);
      } else {
        zone(child, 1, kNoZone);
      }
    } else if (name == "trace") {
      trace(child);
    } else {
      xml_.unexpected(child, e, {"config", "zone", "AS", "cluster", "trace"});
    }
  });
}

void SgReader::config(const pugi::xml_node& e) {
  xml_.check_attributes(e, {"id"});
  SgProps props;
  std::unordered_set<std::string> ids;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "prop") xml_.unexpected(child, e, {"prop"});
    prop(child, props, ids);
    xml_.warn(child, "ignored: SimGrid's configuration tunes SimGrid's models, not pcsim's");
  });
}

void SgReader::zone(const pugi::xml_node& e, int depth, std::size_t parent) {
  if (depth > kMaxZoneDepth) xml_.fail(e, fmt::format("zones nested more than {} deep", kMaxZoneDepth));
  xml_.check_attributes(e, {"id", "routing"});
  const SgRouting routing = routing_of(e);
  const std::size_t serial = declare_zone(e, parent, routing);
  StarDraft star;
  star.cluster = routing == SgRouting::Cluster;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) { zone_child(child, e, depth, serial, star); });
  if (star.cluster) finish_star(serial, star);
}

void SgReader::zone_child(const pugi::xml_node& child, const pugi::xml_node& e, int depth, std::size_t zone, StarDraft& star) {
  const std::string_view name = child.name();
  const SgRouting routing = platform_.zones[zone].routing;
  const bool routed = routing != SgRouting::None && routing != SgRouting::Cluster;
  if (name == "prop") {
    SgProps ignored;
    std::unordered_set<std::string> prop_ids;  // SimGrid takes a zone's props one by one, a repeated id overriding
    prop(child, ignored, prop_ids);
    xml_.warn(child, "ignored: a property of a zone cannot change a result");
  } else if (name == "zone" || name == "AS") {
    this->zone(child, depth + 1, zone);
  } else if (name == "cluster") {
    cluster(child, zone);
  } else if (name == "host") {
    host(child, zone);
  } else if (name == "router") {
    router(child, zone);
  } else if (name == "link") {
    link(child);
  } else if (name == "trace") {
    trace(child);
  } else if (name == "host_link" && star.cluster) {
    host_link(child, zone, star);
  } else if (name == "backbone" && star.cluster) {
    backbone(child, star);
  } else if (name == "cabinet" && star.cluster) {
    xml_.check_attributes(child, {"id", "prefix", "suffix", "radical", "speed", "bw", "lat"});
    xml_.check_empty(child);
    star.cabinets.push_back(child);
  } else if (name == "host_link" || name == "backbone" || name == "cabinet") {
    xml_.fail(child, "only a zone with routing=\"Cluster\" takes it");
  } else if (name == "route" || name == "zoneRoute" || name == "ASroute") {
    if (routing == SgRouting::None) xml_.fail(child, "a zone with routing=\"None\" has no routes");
    if (!routed) xml_.fail(child, "a zone with routing=\"Cluster\" routes through its <host_link>s, not routes");
    if (name == "route") {
      route(child, zone);
    } else {
      zone_route(child, zone, false);
    }
  } else if (name == "bypassRoute") {
    bypass_route(child, zone);
  } else if (name == "bypassZoneRoute" || name == "bypassASroute") {
    zone_route(child, zone, true);
  } else {
    xml_.unexpected(child, e, {"prop", "zone", "AS", "cluster", "host", "router", "link", "route", "zoneRoute", "bypassRoute", "bypassZoneRoute",
                               "host_link", "backbone", "cabinet", "trace"});
  }
}

// SimGrid's routing kinds; Vivaldi and Wifi model what pcsim cannot (see README, SimGrid platforms).
SgRouting SgReader::routing_of(const pugi::xml_node& e) {
  const std::string routing = xml_.required(e, "routing");
  // SimGrid compares the names without case ("WIFI" is its Wifi).
  const auto is = [&](std::string_view name) {
    return routing.size() == name.size() &&
           std::equal(routing.begin(), routing.end(), name.begin(), [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b)); });
  };
  if (is("Full")) return SgRouting::Full;
  if (is("Floyd")) return SgRouting::Floyd;
  if (is("Dijkstra")) return SgRouting::Dijkstra;
  if (is("DijkstraCache")) return SgRouting::DijkstraCache;
  if (is("Cluster")) return SgRouting::Cluster;
  if (is("None")) return SgRouting::None;
  if (is("Vivaldi")) xml_.fail_attribute(e, "routing", "Vivaldi is refused: its latencies come from host coordinates, which pcsim does not model");
  if (is("Wifi")) xml_.fail_attribute(e, "routing", "Wifi is refused: its hosts share one medium at rates of their own, which pcsim does not model");
  xml_.fail_attribute(e, "routing", fmt::format("routing '{}' is not one of Full, Floyd, Dijkstra, DijkstraCache, Cluster, None", sg_shown(routing)));
}

// Zones and clusters share SimGrid's namespace of netpoints with hosts and routers; returns the zone's index.
std::size_t SgReader::declare_zone(const pugi::xml_node& e, std::size_t parent, SgRouting routing) {
  const std::string id = xml_.required(e, "id");
  SgZone z;
  z.id = id;
  z.routing = routing;
  z.parent = parent;
  z.line = xml_.line(e);
  const std::size_t index = platform_.zones.size();
  add_member(parent, {SgNetpoint::Kind::Zone, index}, id, e, "id");
  platform_.zones.push_back(std::move(z));
  return index;
}

// A netpoint joins its zone (the root zone has none), its name taken.
void SgReader::add_member(std::size_t zone, SgNetpoint n, const std::string& id, const pugi::xml_node& e, const char* attribute) {
  const auto [it, added] = netpoint_at_.emplace(id, n);
  if (!added) {
    const SgNetpoint first = it->second;
    const char* kind = first.kind == SgNetpoint::Kind::Host ? "host" : first.kind == SgNetpoint::Kind::Router ? "router" : "zone";
    const int line = first.kind == SgNetpoint::Kind::Host     ? platform_.hosts[first.index].line
                     : first.kind == SgNetpoint::Kind::Router ? platform_.routers[first.index].line
                                                              : platform_.zones[first.index].line;
    if (first.kind == n.kind) xml_.fail_attribute(e, attribute, fmt::format("{} '{}' is declared twice (first at line {})", kind, sg_shown(id), line));
    xml_.fail_attribute(e, attribute, fmt::format("'{}' is already the name of a {} (line {}): hosts, routers and zones share names", sg_shown(id), kind, line));
  }
  if (zone != kNoZone) platform_.zones[zone].members.push_back(n);
}

// A <trace> alone changes nothing: what would apply it (<trace_connect>, a *_file attribute) is refused.
void SgReader::trace(const pugi::xml_node& e) {
  xml_.warn(e, "ignored: a profile changes nothing until connected, and what connects one (<trace_connect>, *_file attributes) is refused");
}

void SgReader::host(const pugi::xml_node& e, std::size_t zone) {
  xml_.check_attributes(e, {"id", "speed", "core", "pstate", "coordinates"}, kHostTraces);
  SgHost h;
  h.id = xml_.required(e, "id");
  h.line = xml_.line(e);
  check_new_host(e, "id", h.id);
  const std::vector<double> speeds = speed_list(e);
  std::size_t pstate = 0;
  if (const auto text = xml_.optional(e, "pstate")) {
    pstate = static_cast<std::size_t>(xml_.whole_number(e, "pstate", *text, 0, static_cast<long long>(speeds.size()) - 1));
  }
  h.speed = speeds[pstate];
  // Other pstates may be 0 (a host switched off, SimGrid's energy examples): pcsim runs at the first.
  if (!(h.speed > 0)) xml_.fail_attribute(e, "speed", fmt::format("the speed of pstate {}, where the host starts, must be greater than 0", pstate));
  if (const auto text = xml_.optional(e, "core")) h.cores = static_cast<int>(xml_.whole_number(e, "core", *text, 1, kMaxCores));
  if (const auto text = xml_.optional(e, "coordinates"); text && !sg_trim(*text).empty()) {
    xml_.warn(e, "attribute coordinates: ignored (only Vivaldi zones use coordinates)");
  }
  std::unordered_set<std::string> prop_ids;
  std::unordered_set<std::string> disk_ids;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    const std::string_view name = child.name();
    if (name == "prop") {
      prop(child, h.props, prop_ids);
      warn_if_energy(child, h.props.back().first);
    } else if (name == "disk") {
      h.disks.push_back(disk(child));
      if (!disk_ids.insert(h.disks.back().id).second) {
        xml_.fail_attribute(child, "id", fmt::format("disk '{}' is declared twice on host '{}'", sg_shown(h.disks.back().id), sg_shown(h.id)));
      }
    } else {
      xml_.unexpected(child, e, {"prop", "disk"});
    }
  });
  add_host(std::move(h), zone, e, "id");
}

SgDisk SgReader::disk(const pugi::xml_node& e) {
  xml_.check_attributes(e, {"id", "read_bw", "write_bw"});
  SgDisk d;
  d.id = e.attribute("id") ? xml_.required(e, "id") : "/";  // SimGrid's default id
  d.line = xml_.line(e);
  d.read_bw = xml_.quantity(e, "read_bw", kSgBandwidth, xml_.required(e, "read_bw"), false);
  d.write_bw = xml_.quantity(e, "write_bw", kSgBandwidth, xml_.required(e, "write_bw"), false);
  std::unordered_set<std::string> prop_ids;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "prop") xml_.unexpected(child, e, {"prop"});
    prop(child, d.props, prop_ids);
  });
  return d;
}

void SgReader::prop(const pugi::xml_node& e, SgProps& props, std::unordered_set<std::string>& ids) {
  xml_.check_attributes(e, {"id", "value"});
  xml_.check_empty(e);
  std::string id = xml_.required(e, "id");
  if (!ids.insert(id).second) xml_.fail_attribute(e, "id", fmt::format("property '{}' is given twice", sg_shown(id)));
  props.emplace_back(std::move(id), xml_.required(e, "value"));
}

void SgReader::warn_if_energy(const pugi::xml_node& e, std::string_view id) {
  if (std::find(std::begin(kEnergyProps), std::end(kEnergyProps), id) != std::end(kEnergyProps)) {
    xml_.warn(e, "ignored: an energy property cannot change a result");
  }
}

// A speed per pstate, "1Gf" or "1Gf, 500Mf, 100Mf".
std::vector<double> SgReader::speed_list(const pugi::xml_node& e) {
  const std::string text = xml_.required(e, "speed");
  std::vector<double> speeds;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    speeds.push_back(xml_.quantity(e, "speed", kSgSpeed, std::string_view(text).substr(start, comma - start), true));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return speeds;
}

SgReader::Policy SgReader::sharing_policy(const pugi::xml_node& e, const char* name, Policy fallback, bool duplex_allowed) {
  const auto text = xml_.optional(e, name);
  if (!text) return fallback;
  if (*text == "SHARED") return Policy::Shared;
  if (*text == "FATPIPE") return Policy::Fatpipe;
  if (duplex_allowed && *text == "SPLITDUPLEX") return Policy::SplitDuplex;
  if (duplex_allowed && *text == "FULLDUPLEX") {
    xml_.warn(e, fmt::format("attribute {}: FULLDUPLEX is SimGrid's deprecated spelling of SPLITDUPLEX", name));
    return Policy::SplitDuplex;
  }
  if (*text == "WIFI") xml_.fail_attribute(e, name, "WIFI is not supported");
  xml_.fail_attribute(e, name, fmt::format("'{}' is not one of {}", sg_shown(*text), duplex_allowed ? "SHARED, SPLITDUPLEX, FATPIPE" : "SHARED, FATPIPE"));
}

void SgReader::link(const pugi::xml_node& e) {
  xml_.check_attributes(e, {"id", "bandwidth", "latency", "sharing_policy"}, kLinkTraces);
  SgLink l;
  l.id = xml_.required(e, "id");
  l.line = xml_.line(e);
  l.bandwidth = xml_.quantity(e, "bandwidth", kSgBandwidth, xml_.required(e, "bandwidth"), false);
  if (const auto text = xml_.optional(e, "latency")) l.latency = xml_.quantity(e, "latency", kSgTime, *text, true);
  const Policy policy = sharing_policy(e, "sharing_policy", Policy::Shared, true);
  l.sharing = policy == Policy::Fatpipe ? LinkSharing::Fatpipe : LinkSharing::Shared;
  std::unordered_set<std::string> prop_ids;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "prop") xml_.unexpected(child, e, {"prop"});
    prop(child, l.props, prop_ids);
  });
  if (policy == Policy::SplitDuplex) {
    add_split_duplex(std::move(l), e, "id");
  } else {
    add_link(std::move(l), e, "id");
  }
}

void SgReader::check_new_host(const pugi::xml_node& e, const char* attribute, const std::string& id) {
  if (const auto it = host_at_.find(id); it != host_at_.end()) {
    xml_.fail_attribute(e, attribute, fmt::format("host '{}' is declared twice (first at line {})", sg_shown(id), platform_.hosts[it->second].line));
  }
  if (platform_.hosts.size() >= limits_.max_hosts) xml_.fail(e, fmt::format("more than {} hosts", limits_.max_hosts));
}

void SgReader::add_host(SgHost h, std::size_t zone, const pugi::xml_node& e, const char* attribute) {
  h.zone = zone;
  add_member(zone, {SgNetpoint::Kind::Host, platform_.hosts.size()}, h.id, e, attribute);
  host_at_.emplace(h.id, platform_.hosts.size());
  platform_.hosts.push_back(std::move(h));
}

void SgReader::add_link(SgLink l, const pugi::xml_node& e, const char* attribute) {
  const auto first_line = [&]() -> int {
    if (const auto it = link_at_.find(l.id); it != link_at_.end()) return platform_.links[it->second].line;
    if (const auto it = duplex_lines_.find(l.id); it != duplex_lines_.end()) return it->second;
    return 0;
  };
  if (const int first = first_line()) xml_.fail_attribute(e, attribute, fmt::format("link '{}' is declared twice (first at line {})", sg_shown(l.id), first));
  link_at_.emplace(l.id, platform_.links.size());
  platform_.links.push_back(std::move(l));
}

// A SPLITDUPLEX link is two: <id>_UP and <id>_DOWN, SimGrid's names.
void SgReader::add_split_duplex(SgLink l, const pugi::xml_node& e, const char* attribute) {
  const auto it = link_at_.find(l.id);
  const auto duplex = duplex_lines_.find(l.id);
  if (it != link_at_.end() || duplex != duplex_lines_.end()) {
    xml_.fail_attribute(e, attribute, fmt::format("link '{}' is declared twice (first at line {})", sg_shown(l.id),
                                                  it != link_at_.end() ? platform_.links[it->second].line : duplex->second));
  }
  SgLink down = l;
  down.id = l.id + "_DOWN";
  down.half = DuplexHalf::Down;
  down.duplex_id = l.id;
  l.half = DuplexHalf::Up;
  l.duplex_id = l.id;
  l.id += "_UP";
  const int line = l.line;
  add_link(std::move(l), e, attribute);
  add_link(std::move(down), e, attribute);
  duplex_lines_.emplace(platform_.links.back().duplex_id, line);
}

SgPlatform read_simgrid_platform(const std::string& text, const std::string& file, const SgLimits& limits) {
  return SgReader(text, file, limits).read();
}

SgPlatform read_simgrid_platform(const std::string& text, const std::string& file) { return read_simgrid_platform(text, file, SgLimits{}); }

}  // namespace pagecache::formats::simgrid
