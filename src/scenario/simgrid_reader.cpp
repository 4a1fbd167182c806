// read_simgrid_platform: SimGrid platform XML -> SgPlatform, in one pass over the elements in
// document order, so that a route sees only the hosts and links declared before it, as in
// SimGrid (whose parser is a SAX parser building the platform as it reads).

#include "scenario/simgrid_reader.hpp"

#include "scenario/simgrid_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iterator>

namespace pagecache::scenario {

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

std::uint64_t pair_key(std::size_t a, std::size_t b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b); }

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
        cluster(child);
      } else {
        zone(child, 1);
      }
    } else {
      xml_.unexpected(child, e, {"config", "zone", "AS", "cluster"});
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

void SgReader::zone(const pugi::xml_node& e, int depth) {
  if (depth > kMaxZoneDepth) xml_.fail(e, fmt::format("zones nested more than {} deep", kMaxZoneDepth));
  xml_.check_attributes(e, {"id", "routing"});
  const std::size_t serial = declare_zone(e);
  const std::string routing = xml_.required(e, "routing");
  if (routing != "Full" && routing != "None") {
    xml_.fail_attribute(e, "routing", fmt::format("routing '{}' is not supported (only Full)", sg_shown(routing)));
  }
  // SimGrid's DTD: a zone holds zones and clusters, or hosts and routes (links in both).
  bool leaf = false;
  bool inner = false;
  const auto kind = [&](const pugi::xml_node& child, bool is_leaf) {
    (is_leaf ? leaf : inner) = true;
    if (leaf && inner) xml_.fail(child, "a zone holds either hosts and routes, or zones and clusters, not both");
  };
  std::unordered_set<std::string> prop_ids;
  SgProps ignored;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    const std::string_view name = child.name();
    if (name == "prop") {
      prop(child, ignored, prop_ids);
      xml_.warn(child, "ignored: a property of a Full zone cannot change a result");
    } else if (name == "zone" || name == "AS") {
      kind(child, false);
      zone(child, depth + 1);
    } else if (name == "cluster") {
      kind(child, false);
      cluster(child);
    } else if (name == "host") {
      kind(child, true);
      host(child, serial);
    } else if (name == "link") {
      link(child);
    } else if (name == "route") {
      kind(child, true);
      if (routing == "None") xml_.fail(child, "a zone with routing=\"None\" has no routes");
      route(child, serial);
    } else {
      xml_.unexpected(child, e, {"prop", "zone", "AS", "cluster", "host", "link", "route"});
    }
  });
}

// Zones and clusters share SimGrid's namespace of netzones; returns the zone's serial.
std::size_t SgReader::declare_zone(const pugi::xml_node& e) {
  const std::string id = xml_.required(e, "id");
  const auto [it, added] = zone_lines_.emplace(id, xml_.line(e));
  if (!added) xml_.fail_attribute(e, "id", fmt::format("zone '{}' is declared twice (first at line {})", sg_shown(id), it->second));
  zone_ids_.push_back(id);
  return zone_ids_.size() - 1;
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
  add_host(std::move(h), zone);
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
    speeds.push_back(xml_.quantity(e, "speed", kSgSpeed, std::string_view(text).substr(start, comma - start), false));
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

void SgReader::route(const pugi::xml_node& e, std::size_t zone) {
  xml_.check_attributes(e, {"src", "dst", "symmetrical"});
  SgRoute r;
  r.src = xml_.required(e, "src");
  r.dst = xml_.required(e, "dst");
  r.line = xml_.line(e);
  const std::size_t src = route_end(e, "src", r.src, zone);
  const std::size_t dst = route_end(e, "dst", r.dst, zone);
  if (const auto text = xml_.optional(e, "symmetrical")) {
    if (*text == "NO" || *text == "no") {
      r.symmetrical = false;
    } else if (*text != "YES" && *text != "yes") {
      xml_.fail_attribute(e, "symmetrical", fmt::format("'{}' is not YES or NO", sg_shown(*text)));
    }
  }
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "link_ctn") xml_.unexpected(child, e, {"link_ctn"});
    r.links.push_back(link_in_route(child));
  });
  if (r.links.empty()) xml_.fail(e, "a route between hosts with no link");
  // SimGrid's FullZone refuses a second route for a direction, the reverse of a symmetrical one included.
  const auto taken = [&](std::size_t from, std::size_t to) {
    const auto it = route_lines_.find(pair_key(from, to));
    return it == route_lines_.end() ? 0 : it->second;
  };
  if (const int first = taken(src, dst)) {
    xml_.fail(e, fmt::format("a second route from '{}' to '{}' (the first at line {}; routes are symmetrical unless symmetrical=\"NO\")",
                             sg_shown(r.src), sg_shown(r.dst), first));
  }
  if (r.symmetrical && src != dst) {
    if (const int first = taken(dst, src)) {
      xml_.fail(e, fmt::format("the route from '{}' to '{}' is declared at line {}: declare this one symmetrical=\"NO\"", sg_shown(r.dst),
                               sg_shown(r.src), first));
    }
    route_lines_.emplace(pair_key(dst, src), r.line);
  }
  route_lines_.emplace(pair_key(src, dst), r.line);
  platform_.routes.push_back(std::move(r));
}

std::size_t SgReader::route_end(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t zone) {
  const auto it = host_at_.find(id);
  if (it == host_at_.end()) xml_.fail_attribute(e, attribute, fmt::format("unknown host '{}' (declare hosts before their routes)", sg_shown(id)));
  if (host_zone_[it->second] != zone) {
    xml_.fail_attribute(e, attribute, fmt::format("host '{}' is in zone '{}', not in this route's zone '{}' (routes between zones are not supported)",
                                                  sg_shown(id), sg_shown(zone_ids_[host_zone_[it->second]]), sg_shown(zone_ids_[zone])));
  }
  return it->second;
}

// A <link_ctn>: a link, or with direction="UP" or "DOWN" a half of a SPLITDUPLEX link.
std::string SgReader::link_in_route(const pugi::xml_node& e) {
  xml_.check_attributes(e, {"id", "direction"});
  xml_.check_empty(e);
  const std::string id = xml_.required(e, "id");
  const std::string direction = xml_.optional(e, "direction").value_or("NONE");
  if (direction != "NONE" && direction != "UP" && direction != "DOWN") {
    xml_.fail_attribute(e, "direction", fmt::format("'{}' is not UP, DOWN or NONE", sg_shown(direction)));
  }
  const bool duplex = duplex_lines_.count(id) != 0;
  const auto plain = link_at_.find(id);
  if (!duplex && plain == link_at_.end()) xml_.fail_attribute(e, "id", fmt::format("unknown link '{}' (declare links before their routes)", sg_shown(id)));
  if (direction == "NONE") {
    if (duplex) xml_.fail_attribute(e, "direction", fmt::format("link '{}' is SPLITDUPLEX: say which half, UP or DOWN", sg_shown(id)));
    const SgLink& l = platform_.links[plain->second];
    // SimGrid takes a half named so as a plain link, which its symmetrical routes do not swap: refused, to keep one rule.
    if (l.half != DuplexHalf::None) {
      xml_.fail_attribute(e, "id", fmt::format("'{}' is a half of SPLITDUPLEX link '{}': write id=\"{}\" direction=\"{}\"", sg_shown(id),
                                               sg_shown(l.duplex_id), sg_shown(l.duplex_id), l.half == DuplexHalf::Up ? "UP" : "DOWN"));
    }
    return id;
  }
  if (!duplex) xml_.fail_attribute(e, "direction", fmt::format("link '{}' is not SPLITDUPLEX: only those have directions", sg_shown(id)));
  return id + "_" + direction;
}

void SgReader::check_new_host(const pugi::xml_node& e, const char* attribute, const std::string& id) {
  if (const auto it = host_at_.find(id); it != host_at_.end()) {
    xml_.fail_attribute(e, attribute, fmt::format("host '{}' is declared twice (first at line {})", sg_shown(id), platform_.hosts[it->second].line));
  }
  if (platform_.hosts.size() >= limits_.max_hosts) xml_.fail(e, fmt::format("more than {} hosts", limits_.max_hosts));
}

void SgReader::add_host(SgHost h, std::size_t zone) {
  host_at_.emplace(h.id, platform_.hosts.size());
  host_zone_.push_back(zone);
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

}  // namespace pagecache::scenario
