// A SimGrid <cluster> (FLAT topology only) expanded as SimGrid expands it: a host per radical,
// named prefix + radical + suffix, each with its private link (SPLITDUPLEX by default) and, if
// the cluster asks for them, a loopback and a limiter; a backbone shared by all.

#include "formats/simgrid/xml/reader.hpp"

#include "formats/simgrid/xml/radical.hpp"
#include "formats/simgrid/xml/text.hpp"
#include "formats/simgrid/routing/topology.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::formats::simgrid {

// The links of a cluster as its attributes give them. SimGrid makes a backbone, a limiter or a
// loopback when one of its values is above 0.
struct SgReader::ClusterLinks {
  SgLink link;  // each node's private link, its id not yet given
  Policy policy = Policy::SplitDuplex;
  double bb_bw = 0.0;
  double bb_lat = 0.0;
  Policy bb_policy = Policy::Shared;
  double limiter_bw = 0.0;
  double loopback_bw = 0.0;
  double loopback_lat = 0.0;
};

void SgReader::cluster(const pugi::xml_node& e, std::size_t parent) {
  xml_.check_attributes(e, {"id", "prefix", "suffix", "radical", "speed", "core", "bw", "lat", "sharing_policy", "topology", "topo_parameters",
                            "bb_bw", "bb_lat", "bb_sharing_policy", "router_id", "limiter_link", "loopback_bw", "loopback_lat"});
  const std::size_t zone = declare_zone(e, parent, SgRouting::Cluster);
  platform_.zones[zone].cluster = platform_.clusters.size();
  const std::string id = platform_.zones[zone].id;
  const int line = xml_.line(e);
  const std::string prefix = xml_.present(e, "prefix");
  const std::string suffix = xml_.present(e, "suffix");
  const SgTopology topology = cluster_topology(e);
  SgHost node = cluster_node(e, id, line);
  const ClusterLinks links = cluster_links(e, line);
  SgCluster c = cluster_record(e, id, line, links);
  c.zone = zone;
  c.topology = topology;
  if (topology != SgTopology::Flat) {
    expand_topology(e, c, zone, std::move(node), links, prefix, suffix);
    platform_.clusters.push_back(std::move(c));
    return;
  }
  expand_cluster(e, c, zone, std::move(node), links, prefix, suffix);
  // SimGrid's gateway of the cluster, after its hosts: router_id, else a name made as its hosts' are.
  const std::string router_id{sg_trim(xml_.optional(e, "router_id").value_or(""))};
  c.router = router_id.empty() ? prefix + id + "_router" + suffix : router_id;
  add_member(zone, {SgNetpoint::Kind::Router, platform_.routers.size()}, c.router, e, router_id.empty() ? "id" : "router_id");
  platform_.routers.push_back({c.router, zone, line});
  platform_.clusters.push_back(std::move(c));
}

SgTopology SgReader::cluster_topology(const pugi::xml_node& e) {
  const std::string topology = xml_.optional(e, "topology").value_or("FLAT");
  if (topology == "TORUS") return SgTopology::Torus;
  if (topology == "FAT_TREE") return SgTopology::FatTree;
  if (topology == "DRAGONFLY") return SgTopology::Dragonfly;
  if (topology != "FLAT") xml_.fail_attribute(e, "topology", fmt::format("'{}' is not one of FLAT, TORUS, FAT_TREE, DRAGONFLY", sg_shown(topology)));
  if (!sg_trim(xml_.optional(e, "topo_parameters").value_or("")).empty()) xml_.warn(e, "attribute topo_parameters: ignored by a FLAT cluster");
  return SgTopology::Flat;
}

// What every node of the cluster is, its id aside: speed, cores and the cluster's props.
SgHost SgReader::cluster_node(const pugi::xml_node& e, const std::string& id, int line) {
  SgHost node;
  node.cluster = id;
  node.line = line;
  node.speed = speed_list(e).front();
  if (!(node.speed > 0)) xml_.fail_attribute(e, "speed", "the speed of pstate 0, where the hosts start, must be greater than 0");
  if (const auto text = xml_.optional(e, "core")) node.cores = static_cast<int>(xml_.whole_number(e, "core", *text, 1, kMaxCores));
  std::unordered_set<std::string> prop_ids;
  xml_.for_each_element(e, [&](const pugi::xml_node& child) {
    if (std::string_view(child.name()) != "prop") xml_.unexpected(child, e, {"prop"});
    prop(child, node.props, prop_ids);
    warn_if_energy(child, node.props.back().first);
  });
  return node;
}

SgReader::ClusterLinks SgReader::cluster_links(const pugi::xml_node& e, int line) {
  ClusterLinks links;
  SgLink& link = links.link;
  link.line = line;
  link.bandwidth = xml_.quantity(e, "bw", kSgBandwidth, xml_.required(e, "bw"), false);
  link.latency = xml_.quantity(e, "lat", kSgTime, xml_.required(e, "lat"), true);
  links.policy = sharing_policy(e, "sharing_policy", Policy::SplitDuplex, true);
  link.sharing = links.policy == Policy::Fatpipe ? LinkSharing::Fatpipe : LinkSharing::Shared;

  const auto optional_quantity = [&](const char* name, const SgQuantity& q) {
    const auto text = xml_.optional(e, name);
    return text && !sg_trim(*text).empty() ? xml_.quantity(e, name, q, *text, true) : 0.0;
  };
  links.bb_bw = optional_quantity("bb_bw", kSgBandwidth);
  links.bb_lat = optional_quantity("bb_lat", kSgTime);
  links.limiter_bw = optional_quantity("limiter_link", kSgBandwidth);
  links.loopback_bw = optional_quantity("loopback_bw", kSgBandwidth);
  links.loopback_lat = optional_quantity("loopback_lat", kSgTime);
  links.bb_policy = sharing_policy(e, "bb_sharing_policy", Policy::Shared, false);
  if (links.bb_lat > 0 && links.bb_bw == 0) xml_.fail_attribute(e, "bb_lat", "a backbone needs bb_bw above 0");
  if (links.loopback_lat > 0 && links.loopback_bw == 0) xml_.fail_attribute(e, "loopback_lat", "a loopback needs loopback_bw above 0");
  return links;
}

// The cluster as SgPlatform keeps it: its links' kinds and its radicals, at most as many as
// the platform has room for; its first host the next one added.
SgCluster SgReader::cluster_record(const pugi::xml_node& e, const std::string& id, int line, const ClusterLinks& links) {
  SgCluster c;
  c.id = id;
  c.line = line;
  c.split_duplex = links.policy == Policy::SplitDuplex;
  c.backbone = links.bb_bw > 0;
  c.limiter = links.limiter_bw > 0;
  c.loopback = links.loopback_bw > 0;
  const std::size_t room = std::min(limits_.max_cluster_hosts, limits_.max_hosts - std::min(limits_.max_hosts, platform_.hosts.size()));
  try {
    c.radicals = parse_sg_radical(xml_.required(e, "radical"), room);
  } catch (const ConfigError& error) {
    xml_.fail_attribute(e, "radical", error.what());
  }
  c.first_host = platform_.hosts.size();
  return c;
}

// Links in SimGrid's order of creation: the backbone, then per node loopback, limiter, private link.
void SgReader::expand_cluster(const pugi::xml_node& e, SgCluster& c, std::size_t zone, SgHost node, const ClusterLinks& links,
                              const std::string& prefix, const std::string& suffix) {
  const std::string& id = c.id;
  const int line = c.line;
  if (c.backbone) {
    add_link(SgLink{id + "_backbone", links.bb_bw, links.bb_lat, links.bb_policy == Policy::Fatpipe ? LinkSharing::Fatpipe : LinkSharing::Shared,
                    DuplexHalf::None, "", {}, line},
             e, "id");
  }
  SgLink link = links.link;
  // Room made once: a cluster may have 10^5 nodes.
  const std::size_t per_node = (c.split_duplex ? 2 : 1) + (c.loopback ? 1 : 0) + (c.limiter ? 1 : 0);
  platform_.hosts.reserve(platform_.hosts.size() + c.size());
  platform_.links.reserve(platform_.links.size() + per_node * c.size());
  host_at_.reserve(host_at_.size() + c.size());
  netpoint_at_.reserve(netpoint_at_.size() + c.size());
  link_at_.reserve(link_at_.size() + per_node * c.size());
  if (c.split_duplex) duplex_lines_.reserve(duplex_lines_.size() + c.size());
  platform_.zones[zone].members.reserve(c.size() + 1);
  for (const int radical : c.radicals) {
    node.id = prefix + std::to_string(radical) + suffix;
    check_new_host(e, "radical", node.id);
    add_host(node, zone, e, "radical");
    const std::string link_id = id + "_link_" + std::to_string(radical);
    if (c.loopback) {
      add_link(SgLink{link_id + "_loopback", links.loopback_bw, links.loopback_lat, LinkSharing::Fatpipe, DuplexHalf::None, "", {}, line}, e, "id");
    }
    if (c.limiter) add_link(SgLink{link_id + "_limiter", links.limiter_bw, 0.0, LinkSharing::Shared, DuplexHalf::None, "", {}, line}, e, "id");
    link.id = link_id;
    if (c.split_duplex) {
      add_split_duplex(link, e, "id");
    } else {
      add_link(link, e, "id");
    }
  }
}

// A TORUS, FAT_TREE or DRAGONFLY cluster: its hosts, one per element of the topology, then its
// links in SimGrid's order (formats/simgrid/routing/topology.hpp). SimGrid makes no router for these.
void SgReader::expand_topology(const pugi::xml_node& e, SgCluster& c, std::size_t zone, SgHost node, const ClusterLinks& links,
                               const std::string& prefix, const std::string& suffix) {
  std::size_t nodes = 0;
  try {
    nodes = sg_topology_nodes(c, xml_.optional(e, "topo_parameters").value_or(""));
  } catch (const ConfigError& error) {
    xml_.fail_attribute(e, "topo_parameters", error.what());
  }
  if (nodes > c.radicals.size()) {
    xml_.fail_attribute(e, "radical", fmt::format("{} nodes for a topology of {} (SimGrid refuses it too)", c.radicals.size(), nodes));
  }
  // Bounded as nodes are: a few numbers could ask for 10^12 switches and links.
  const double most = 16.0 * static_cast<double>(limits_.max_cluster_hosts);
  if (const double size = sg_topology_size(c); size > most) {
    xml_.fail_attribute(e, "topo_parameters", fmt::format("{:g} links and switches, more than the {:g} pcsim takes", size, most));
  }
  if (nodes < c.radicals.size()) {
    xml_.warn(e, fmt::format("attribute radical: {} nodes, of which the topology takes the first {}, as SimGrid does", c.radicals.size(), nodes));
    c.radicals.resize(nodes);
  }
  if (links.bb_bw > 0) xml_.warn(e, "attribute bb_bw: ignored by a cluster with a topology, as SimGrid ignores it");
  if (!sg_trim(xml_.optional(e, "router_id").value_or("")).empty()) xml_.warn(e, "attribute router_id: ignored (SimGrid makes no router for a cluster with a topology)");
  if (c.topology == SgTopology::FatTree) c.link_serial = fat_tree_links_, c.position_base = fat_tree_positions_;
  if (c.topology == SgTopology::Dragonfly) c.link_serial = dragonfly_links_;
  for (std::size_t k = 0; k < c.size(); ++k) {
    node.id = prefix + std::to_string(c.radicals[k]) + suffix;
    check_new_host(e, "radical", node.id);
    add_host(node, zone, e, "radical");
  }
  std::size_t made = 0;
  const LinkSharing sharing = links.policy == Policy::Fatpipe ? LinkSharing::Fatpipe : LinkSharing::Shared;
  for (const SgTopologyLink& t : sg_topology_links(c)) {
    SgLink l{t.id, links.link.bandwidth * t.bandwidth_factor, links.link.latency, sharing, DuplexHalf::None, "", {}, c.line};
    if (t.kind == SgTopologyLink::Kind::Loopback) l.bandwidth = links.loopback_bw, l.latency = links.loopback_lat, l.sharing = LinkSharing::Fatpipe;
    if (t.kind == SgTopologyLink::Kind::Limiter) l.bandwidth = links.limiter_bw, l.latency = 0.0, l.sharing = LinkSharing::Shared;
    made += t.kind == SgTopologyLink::Kind::Private ? 1 : 0;
    add_link(std::move(l), e, "id");
  }
  const std::size_t serials = c.split_duplex ? made / 2 : made;
  if (c.topology == SgTopology::FatTree) fat_tree_links_ += serials, fat_tree_positions_ += static_cast<long>(c.size());
  if (c.topology == SgTopology::Dragonfly) dragonfly_links_ += serials;
}

}  // namespace pagecache::formats::simgrid
