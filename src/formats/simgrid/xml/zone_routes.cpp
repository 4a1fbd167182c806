// What routes are made of in a SimGrid zone: routers, <route>s between its hosts and routers,
// <zoneRoute>s between its sub-zones through their gateways, bypasses, and a Cluster zone's
// star of <host_link>s around its <backbone>. Each is checked as SimGrid's zones check them
// when they are added (RoutedZone::add_route_check_params, StarZone, add_bypass_route).

#include "formats/simgrid/xml/reader.hpp"

#include "formats/simgrid/xml/radical.hpp"
#include "formats/simgrid/xml/text.hpp"

#include <pagecache/error.hpp>

#include <algorithm>

#include <fmt/format.h>

namespace pagecache::formats::simgrid {

namespace {

std::string route_key(const std::string& src, const std::string& dst) { return src + '\n' + dst; }

}  // namespace

void SgReader::router(const pugi::xml_node& e, std::size_t zone) {
  xml_.check_attributes(e, {"id", "coordinates"});
  xml_.check_empty(e);
  SgRouter r{xml_.required(e, "id"), zone, xml_.line(e)};
  if (const auto text = xml_.optional(e, "coordinates"); text && !sg_trim(*text).empty()) {
    xml_.warn(e, "attribute coordinates: ignored (only Vivaldi zones use coordinates)");
  }
  add_member(zone, {SgNetpoint::Kind::Router, platform_.routers.size()}, r.id, e, "id");
  platform_.routers.push_back(std::move(r));
}

// A route's symmetrical attribute: YES (SimGrid's default) or NO, in either case.
bool SgReader::symmetrical(const pugi::xml_node& e) {
  const auto text = xml_.optional(e, "symmetrical");
  if (!text || *text == "YES" || *text == "yes") return true;
  if (*text != "NO" && *text != "no") xml_.fail_attribute(e, "symmetrical", fmt::format("'{}' is not YES or NO", sg_shown(*text)));
  return false;
}

void SgReader::route(const pugi::xml_node& e, std::size_t zone) {
  xml_.check_attributes(e, {"src", "dst", "symmetrical"});
  SgRoute r;
  r.src = xml_.required(e, "src");
  r.dst = xml_.required(e, "dst");
  r.line = xml_.line(e);
  r.zone = zone;
  const SgNetpoint src = route_end(e, "src", r.src, zone);
  const SgNetpoint dst = route_end(e, "dst", r.dst, zone);
  r.symmetrical = symmetrical(e);
  r.links = links_of(e);
  if (r.links.empty()) xml_.fail(e, "a route between hosts with no link");
  check_new_route(e, r);
  // Routes between hosts of a Full zone are as written: find_route returns them as they are.
  const bool hosts = src.kind == SgNetpoint::Kind::Host && dst.kind == SgNetpoint::Kind::Host;
  (hosts && platform_.zones[zone].routing == SgRouting::Full ? platform_.routes : platform_.zone_routes).push_back(std::move(r));
}

// SimGrid's zones refuse a second route for a direction, the reverse of a symmetrical one included.
void SgReader::check_new_route(const pugi::xml_node& e, const SgRoute& r) {
  const auto taken = [&](const std::string& from, const std::string& to) {
    const auto it = route_lines_.find(route_key(from, to));
    return it == route_lines_.end() ? 0 : it->second;
  };
  if (const int first = taken(r.src, r.dst)) {
    xml_.fail(e, fmt::format("a second route from '{}' to '{}' (the first at line {}; routes are symmetrical unless symmetrical=\"NO\")",
                             sg_shown(r.src), sg_shown(r.dst), first));
  }
  if (r.symmetrical && r.src != r.dst) {
    if (const int first = taken(r.dst, r.src)) {
      xml_.fail(e, fmt::format("the route from '{}' to '{}' is declared at line {}: declare this one symmetrical=\"NO\"", sg_shown(r.dst),
                               sg_shown(r.src), first));
    }
    route_lines_.emplace(route_key(r.dst, r.src), r.line);
  }
  route_lines_.emplace(route_key(r.src, r.dst), r.line);
}

// A <route>'s end: a host or router of the route's own zone.
SgNetpoint SgReader::route_end(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t zone) {
  const auto it = netpoint_at_.find(id);
  if (it == netpoint_at_.end()) xml_.fail_attribute(e, attribute, fmt::format("unknown host '{}' (declare hosts before their routes)", sg_shown(id)));
  const SgNetpoint n = it->second;
  if (n.kind == SgNetpoint::Kind::Zone) {
    xml_.fail_attribute(e, attribute, fmt::format("'{}' is a zone: a route between zones is a <zoneRoute>, with gateways", sg_shown(id)));
  }
  const std::size_t in = n.kind == SgNetpoint::Kind::Host ? platform_.hosts[n.index].zone : platform_.routers[n.index].zone;
  if (in != zone) {
    xml_.fail_attribute(e, attribute, fmt::format("{} '{}' is in zone '{}', not in this route's zone '{}' (a route between zones is a <zoneRoute>)",
                                                  n.kind == SgNetpoint::Kind::Host ? "host" : "router", sg_shown(id),
                                                  sg_shown(platform_.zones[in].id), sg_shown(platform_.zones[zone].id)));
  }
  return n;
}

// <zoneRoute> (<ASroute>) between two sub-zones of this zone, or <bypassZoneRoute> between any
// two zones: links from gw_src, a host or router inside src, to gw_dst inside dst.
void SgReader::zone_route(const pugi::xml_node& e, std::size_t zone, bool bypass) {
  if (bypass) {
    xml_.check_attributes(e, {"src", "dst", "gw_src", "gw_dst"});
  } else {
    xml_.check_attributes(e, {"src", "dst", "gw_src", "gw_dst", "symmetrical"});
  }
  SgRoute r;
  r.src = xml_.required(e, "src");
  r.dst = xml_.required(e, "dst");
  r.gw_src = xml_.required(e, "gw_src");
  r.gw_dst = xml_.required(e, "gw_dst");
  r.line = xml_.line(e);
  r.zone = zone;
  const auto zone_end = [&](const char* attribute, const std::string& id) {
    const auto it = netpoint_at_.find(id);
    if (it == netpoint_at_.end() || it->second.kind != SgNetpoint::Kind::Zone) {
      xml_.fail_attribute(e, attribute, fmt::format("'{}' is not a zone declared before (a <zoneRoute> joins zones)", sg_shown(id)));
    }
    if (!bypass && platform_.zones[it->second.index].parent != zone) {
      xml_.fail_attribute(e, attribute, fmt::format("zone '{}' is not in zone '{}', where the route is", sg_shown(id), sg_shown(platform_.zones[zone].id)));
    }
    return it->second.index;
  };
  check_gateway(e, "gw_src", r.gw_src, zone_end("src", r.src));
  check_gateway(e, "gw_dst", r.gw_dst, zone_end("dst", r.dst));
  if (r.gw_src == r.gw_dst) xml_.fail_attribute(e, "gw_dst", "a route between zones from a gateway to itself");
  r.symmetrical = symmetrical(e);
  r.links = links_of(e);
  if (r.links.empty()) xml_.fail(e, "a route between zones with no link");
  if (bypass) {
    r.symmetrical = false;
    const auto [it, added] = bypass_lines_.emplace(route_key(r.src, r.dst), r.line);
    if (!added) xml_.fail(e, fmt::format("a second bypass from '{}' to '{}' (the first at line {})", sg_shown(r.src), sg_shown(r.dst), it->second));
    platform_.bypass_routes.push_back(std::move(r));
    return;
  }
  check_new_route(e, r);
  platform_.zone_routes.push_back(std::move(r));
}

// A gateway is a host or router inside the zone, at any depth.
void SgReader::check_gateway(const pugi::xml_node& e, const char* attribute, const std::string& id, std::size_t inside) {
  const auto it = netpoint_at_.find(id);
  if (it == netpoint_at_.end() || it->second.kind == SgNetpoint::Kind::Zone) {
    xml_.fail_attribute(e, attribute, fmt::format("'{}' is not a host or router declared before", sg_shown(id)));
  }
  const SgNetpoint n = it->second;
  std::size_t z = n.kind == SgNetpoint::Kind::Host ? platform_.hosts[n.index].zone : platform_.routers[n.index].zone;
  while (z != kNoZone && z != inside) z = platform_.zones[z].parent;
  if (z == kNoZone) xml_.fail_attribute(e, attribute, fmt::format("'{}' is not inside zone '{}'", sg_shown(id), sg_shown(platform_.zones[inside].id)));
}

// <bypassRoute>: between two hosts or routers, oriented, taken before any other route.
void SgReader::bypass_route(const pugi::xml_node& e, std::size_t zone) {
  xml_.check_attributes(e, {"src", "dst"});
  SgRoute r;
  r.src = xml_.required(e, "src");
  r.dst = xml_.required(e, "dst");
  r.line = xml_.line(e);
  r.zone = zone;
  r.symmetrical = false;
  for (const auto& [attribute, id] : {std::pair{"src", r.src}, std::pair{"dst", r.dst}}) {
    const auto it = netpoint_at_.find(id);
    if (it == netpoint_at_.end() || it->second.kind == SgNetpoint::Kind::Zone) {
      xml_.fail_attribute(e, attribute, fmt::format("'{}' is not a host or router declared before", sg_shown(id)));
    }
  }
  r.links = links_of(e);
  if (r.links.empty()) xml_.fail(e, "a bypass with no link");
  const auto [it, added] = bypass_lines_.emplace(route_key(r.src, r.dst), r.line);
  if (!added) xml_.fail(e, fmt::format("a second bypass from '{}' to '{}' (the first at line {})", sg_shown(r.src), sg_shown(r.dst), it->second));
  platform_.bypass_routes.push_back(std::move(r));
}

std::vector<std::string> SgReader::links_of(const pugi::xml_node& e) {
  std::vector<std::string> links;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "link_ctn") xml_.unexpected(child, e, {"link_ctn"});
    links.push_back(link_in_route(child));
  });
  return links;
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

// <host_link id="host" up="link" down="link">: the host's ways to and from the star's centre.
void SgReader::host_link(const pugi::xml_node& e, std::size_t zone, StarDraft& star) {
  xml_.check_attributes(e, {"id", "up", "down"});
  xml_.check_empty(e);
  const std::string id = xml_.required(e, "id");
  const auto host = netpoint_at_.find(id);
  if (host == netpoint_at_.end() || host->second.kind != SgNetpoint::Kind::Host || platform_.hosts[host->second.index].zone != zone) {
    xml_.fail_attribute(e, "id", fmt::format("'{}' is not a host of this zone declared before", sg_shown(id)));
  }
  for (const auto& [h, ways] : star.host_links) {
    if (h == id) xml_.fail_attribute(e, "id", fmt::format("host '{}' has a <host_link> already", sg_shown(id)));
  }
  // SimGrid names the links as they are: a SPLITDUPLEX link's halves are X_UP and X_DOWN.
  const auto named = [&](const char* attribute) {
    const std::string link = xml_.required(e, attribute);
    if (link_at_.count(link) == 0) xml_.fail_attribute(e, attribute, fmt::format("unknown link '{}' (declare links before)", sg_shown(link)));
    return link;
  };
  std::string up = named("up");
  std::string down = named("down");
  star.host_links.push_back({id, {std::move(up), std::move(down)}});
}

// <backbone>: a link every route of the star crosses, one per zone.
void SgReader::backbone(const pugi::xml_node& e, StarDraft& star) {
  xml_.check_attributes(e, {"id", "bandwidth", "latency"});
  xml_.check_empty(e);
  if (!star.backbone.empty()) xml_.fail(e, fmt::format("a second backbone (the first is '{}')", sg_shown(star.backbone)));
  SgLink l;
  l.id = xml_.required(e, "id");
  l.line = xml_.line(e);
  l.bandwidth = xml_.quantity(e, "bandwidth", kSgBandwidth, xml_.required(e, "bandwidth"), false);
  if (const auto text = xml_.optional(e, "latency")) l.latency = xml_.quantity(e, "latency", kSgTime, *text, true);
  star.backbone = l.id;
  add_link(std::move(l), e, "id");
}

// SimGrid builds the star when the zone closes: each host's way up is its up link then the
// backbone, its way down the backbone then its down link.
void SgReader::finish_star(std::size_t zone, StarDraft& draft) {
  for (const pugi::xml_node& e : draft.cabinets) cabinet(e, zone, draft);
  SgStar star;
  star.zone = zone;
  for (auto& [host, links] : draft.host_links) {
    SgStar::Ways ways;
    ways.up.push_back(links.first);
    if (!draft.backbone.empty()) ways.up.push_back(draft.backbone), ways.down.push_back(draft.backbone);
    ways.down.push_back(links.second);
    star.ways.emplace_back(host, std::move(ways));
  }
  platform_.zones[zone].star = platform_.stars.size();
  platform_.stars.push_back(std::move(star));
}

// <cabinet>: hosts prefix + N + suffix, each with links link_<host>_UP and link_<host>_DOWN.
void SgReader::cabinet(const pugi::xml_node& e, std::size_t zone, StarDraft& star) {
  const std::string prefix = xml_.present(e, "prefix");
  const std::string suffix = xml_.present(e, "suffix");
  xml_.required(e, "id");
  SgHost node;
  node.line = xml_.line(e);
  node.speed = xml_.quantity(e, "speed", kSgSpeed, xml_.required(e, "speed"), false);
  SgLink link;
  link.line = node.line;
  link.bandwidth = xml_.quantity(e, "bw", kSgBandwidth, xml_.required(e, "bw"), false);
  link.latency = xml_.quantity(e, "lat", kSgTime, xml_.required(e, "lat"), true);
  std::vector<int> radicals;
  const std::size_t room = std::min(limits_.max_cluster_hosts, limits_.max_hosts - std::min(limits_.max_hosts, platform_.hosts.size()));
  try {
    radicals = parse_sg_radical(xml_.required(e, "radical"), room);
  } catch (const ConfigError& error) {
    xml_.fail_attribute(e, "radical", error.what());
  }
  for (const int radical : radicals) {
    node.id = prefix + std::to_string(radical) + suffix;
    check_new_host(e, "radical", node.id);
    add_host(node, zone, e, "radical");
    link.id = "link_" + node.id + "_UP";
    add_link(link, e, "radical");
    link.id = "link_" + node.id + "_DOWN";
    add_link(link, e, "radical");
    star.host_links.push_back({node.id, {"link_" + node.id + "_UP", "link_" + node.id + "_DOWN"}});
  }
}

}  // namespace pagecache::formats::simgrid
