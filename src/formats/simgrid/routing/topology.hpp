#pragma once
// The cluster topologies TORUS, FAT_TREE and DRAGONFLY as SimGrid's TorusZone, FatTreeZone and
// DragonflyZone build and route them: the links each makes, named and ordered as SimGrid
// creates them, and the route between two of its nodes. A node's limiter is named after its
// position (<cluster>_link_<position>_limiter), its loopback after its radical; a switch's or
// router's limiter after the number SimGrid gives it (counting down from twice the nodes).
// A split-duplex topology link is two plain links X_UP and X_DOWN, as SimGrid makes it.
//
// SimGrid numbers fat-tree and dragonfly links, and fat-tree nodes' positions, with counters
// that run on across the clusters of a platform: SgCluster keeps where each cluster starts.

#include "formats/simgrid/routing/platform.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace pagecache::formats::simgrid {

/// A link a topology makes, in order of creation.
struct SgTopologyLink {
  enum class Kind { Private, Loopback, Limiter };
  std::string id;
  Kind kind = Kind::Private;
  double bandwidth_factor = 1.0;  // a dragonfly link carries the bandwidth of its count of links
};

/// The fat tree of a FAT_TREE cluster: nodes (processing nodes first, then switches level by
/// level) and the links between them.
struct SgFatTree {
  struct Node {
    long id = 0;
    unsigned level = 0;
    long position = 0;
    std::string limiter;             // empty if none
    std::vector<int> label;
    std::vector<long> parents;       // by port: a link index, -1 if none
    std::vector<long> children;      // by port
  };
  struct Link {
    std::size_t child = 0, parent = 0;  // node indices
    std::string up, down;
  };
  std::vector<Node> nodes;
  std::vector<Link> links;  // in order of creation
};

/// The dragonfly of a DRAGONFLY cluster: per router, its links by kind.
struct SgDragonfly {
  struct Router {
    unsigned group = 0, chassis = 0, blade = 0;
    std::string limiter;
    std::vector<std::string> local;  // by node * (2 if split duplex, else 1): up then down
    std::vector<std::string> green;  // by blade
    std::vector<std::string> black;  // by chassis
    std::string blue;
  };
  std::vector<Router> routers;
  std::vector<SgTopologyLink> links;  // the routers' links in order of creation
};

/// Reads topo_parameters for `c.topology` into c.topology_parameters (a problem is thrown as
/// a message for the attribute) and returns how many nodes the topology has.
std::size_t sg_topology_nodes(SgCluster& c, const std::string& parameters);

/// How many links, switches and routers the topology makes beside its nodes (a double: a few
/// numbers ask for more than any memory, which the reader refuses before building).
double sg_topology_size(const SgCluster& c);

SgFatTree sg_fat_tree(const SgCluster& c);
SgDragonfly sg_dragonfly(const SgCluster& c);

/// The route between two nodes of a fat tree (SimGrid's d-mod-k up, then down by label), and
/// of a dragonfly (green, black, blue links to the target's group, then within it).
std::vector<std::string> sg_fat_tree_route(const SgCluster& c, const SgFatTree& tree, std::size_t from, std::size_t to);
std::vector<std::string> sg_dragonfly_route(const SgCluster& c, const SgDragonfly& fly, std::size_t from, std::size_t to);

/// Every link the cluster makes, in SimGrid's order of creation.
std::vector<SgTopologyLink> sg_topology_links(const SgCluster& c);

/// The links from node `from` to node `to` (positions in the cluster); `tree` / `fly` built
/// once for the cluster when it is a fat tree / dragonfly. Empty if SimGrid's rule finds none.
std::vector<std::string> sg_topology_route(const SgCluster& c, const SgFatTree* tree, const SgDragonfly* fly, std::size_t from, std::size_t to);

}  // namespace pagecache::formats::simgrid
