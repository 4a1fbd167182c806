// A FAT_TREE cluster as SimGrid's FatTreeZone builds it (switches level by level, labels,
// links between related nodes port by port) and routes it (d-mod-k up to a common ancestor,
// then down by the destination's label).

#include "formats/simgrid/routing/topology.hpp"

namespace pagecache::formats::simgrid {

namespace {

struct Shape {
  unsigned levels;
  std::vector<unsigned> down, up, count;  // per level: children, parents, links between two related nodes
};

Shape shape_of(const SgCluster& c) {
  const std::vector<unsigned>& p = c.topology_parameters;
  Shape s{p.at(0), {}, {}, {}};
  s.down.assign(p.begin() + 1, p.begin() + 1 + s.levels);
  s.up.assign(p.begin() + 1 + s.levels, p.begin() + 1 + 2 * s.levels);
  s.count.assign(p.begin() + 1 + 2 * s.levels, p.begin() + 1 + 3 * s.levels);
  return s;
}

// A parent is one level up and shares the child's label but for the digit of its own level.
bool related(const Shape& s, const SgFatTree::Node& parent, const SgFatTree::Node& child) {
  if (parent.level != child.level + 1) return false;
  for (unsigned i = 0; i < s.levels; ++i) {
    if (parent.label[i] != child.label[i] && i + 1 != parent.level) return false;
  }
  return true;
}

bool in_sub_tree(const Shape& s, const SgFatTree::Node& root, const SgFatTree::Node& node) {
  if (root.level <= node.level) return false;
  for (unsigned i = 0; i < node.level; ++i) {
    if (root.label[i] != node.label[i]) return false;
  }
  for (unsigned i = root.level; i < s.levels; ++i) {
    if (root.label[i] != node.label[i]) return false;
  }
  return true;
}

// Per level, how many nodes (processing nodes at level 0).
std::vector<std::size_t> nodes_by_level(const Shape& s) {
  std::vector<std::size_t> by_level(s.levels + 1, 1);
  for (unsigned i = 0; i < s.levels; ++i) by_level[0] *= s.down[i];
  for (unsigned i = 0; i < s.levels; ++i) {
    for (unsigned j = 0; j <= i; ++j) by_level[i + 1] *= s.up[j];
    for (unsigned j = i + 1; j < s.levels; ++j) by_level[i + 1] *= s.down[j];
  }
  return by_level;
}

// Labels level by level, counting with digit j in base `down` below the level and `up` above.
void label(const Shape& s, const std::vector<std::size_t>& by_level, SgFatTree& tree) {
  std::size_t k = 0;
  for (unsigned i = 0; i <= s.levels; ++i) {
    std::vector<int> current(s.levels, 0);
    for (std::size_t n = 0; n < by_level[i]; ++n, ++k) {
      tree.nodes[k].label = current;
      for (unsigned pos = 0; pos < s.levels; ++pos) {
        const unsigned most = pos + 1 > i ? s.down[pos] : s.up[pos];
        if (++current[pos] < static_cast<int>(most)) break;
        current[pos] = 0;
      }
    }
  }
}

}  // namespace

SgFatTree sg_fat_tree(const SgCluster& c) {
  const Shape s = shape_of(c);
  const std::vector<std::size_t> by_level = nodes_by_level(s);
  SgFatTree tree;
  for (std::size_t i = 0; i < c.size(); ++i) {
    SgFatTree::Node n;
    n.id = static_cast<long>(i);
    n.position = c.position_base + static_cast<long>(i);
    if (c.limiter) n.limiter = c.id + "_link_" + std::to_string(i) + "_limiter";
    n.parents.assign(static_cast<std::size_t>(s.up[0]) * s.count[0], -1);
    tree.nodes.push_back(std::move(n));
  }
  // Switches numbered down from twice the processing nodes, level by level.
  long number = 2 * static_cast<long>(c.size());
  for (unsigned i = 0; i < s.levels; ++i) {
    for (std::size_t j = 0; j < by_level[i + 1]; ++j) {
      SgFatTree::Node n;
      n.id = --number;
      n.level = i + 1;
      n.position = static_cast<long>(j);
      if (c.limiter) n.limiter = c.id + "_link_" + std::to_string(n.id) + "_limiter";
      n.children.assign(static_cast<std::size_t>(s.down[i]) * s.count[i], -1);
      if (i != s.levels - 1) n.parents.assign(static_cast<std::size_t>(s.up[i + 1]) * s.count[i + 1], -1);
      tree.nodes.push_back(std::move(n));
    }
  }
  label(s, by_level, tree);
  std::size_t serial = c.link_serial;
  std::size_t first_of_level = 0;
  for (unsigned level = 0; level < s.levels; ++level) {
    const std::size_t parents_from = first_of_level + by_level[level];
    for (std::size_t k = first_of_level; k < parents_from; ++k) {
      for (std::size_t q = parents_from; q < parents_from + by_level[level + 1]; ++q) {
        if (!related(s, tree.nodes[q], tree.nodes[k])) continue;
        for (unsigned j = 0; j < s.count[level]; ++j) {
          const std::size_t parent_port = static_cast<std::size_t>(tree.nodes[k].label[level]) + j * s.down[level];
          const std::size_t child_port = static_cast<std::size_t>(tree.nodes[q].label[level]) + j * s.up[level];
          const std::string id = "link_from_" + std::to_string(tree.nodes[k].id) + "_" + std::to_string(tree.nodes[q].id) + "_" + std::to_string(serial++);
          tree.links.push_back({k, q, c.split_duplex ? id + "_UP" : id, c.split_duplex ? id + "_DOWN" : id});
          if (parent_port < tree.nodes[q].children.size()) tree.nodes[q].children[parent_port] = static_cast<long>(tree.links.size() - 1);
          if (child_port < tree.nodes[k].parents.size()) tree.nodes[k].parents[child_port] = static_cast<long>(tree.links.size() - 1);
        }
      }
    }
    first_of_level = parents_from;
  }
  return tree;
}

std::vector<std::string> sg_fat_tree_route(const SgCluster& c, const SgFatTree& tree, std::size_t from, std::size_t to) {
  const Shape s = shape_of(c);
  if (from == to && c.loopback) return {c.id + "_link_" + std::to_string(c.radicals.at(from)) + "_loopback"};
  const SgFatTree::Node& source = tree.nodes[from];
  const SgFatTree::Node& destination = tree.nodes[to];
  std::vector<std::string> route;
  std::size_t current = from;
  // Up: the parent port d-mod-k, from the destination's position.
  for (std::size_t steps = 0; !in_sub_tree(s, tree.nodes[current], destination); ++steps) {
    const SgFatTree::Node& node = tree.nodes[current];
    if (steps > s.levels || node.level >= s.levels) return {};
    long d = destination.position;
    for (unsigned i = 0; i < node.level; ++i) d /= s.up[i];
    d %= static_cast<long>(s.up[node.level]) * s.count[node.level];
    if (d < 0 || node.parents.at(static_cast<std::size_t>(d)) < 0) return {};
    if (!node.limiter.empty()) route.push_back(node.limiter);
    const SgFatTree::Link& link = tree.links[static_cast<std::size_t>(node.parents[static_cast<std::size_t>(d)])];
    route.push_back(link.up);
    current = link.parent;
  }
  // Down: SimGrid scans the children ports from the source's, taking each whose child carries
  // the destination's label digit, and goes on scanning from there in the node it reached.
  for (std::size_t steps = 0; current != to; ++steps) {
    if (steps > s.levels || tree.nodes[current].level == 0) return {};
    const unsigned below = tree.nodes[current].level - 1;
    std::size_t i = static_cast<std::size_t>(source.position % static_cast<long>(s.count[below])) * s.down[below];
    for (; i < tree.nodes[current].children.size(); ++i) {
      const unsigned level = tree.nodes[current].level - 1;
      if (i % s.down[level] != static_cast<std::size_t>(destination.label[level])) continue;
      const long at = tree.nodes[current].children[i];
      if (at < 0) return {};
      const SgFatTree::Link& link = tree.links[static_cast<std::size_t>(at)];
      route.push_back(link.down);
      if (!tree.nodes[current].limiter.empty()) route.push_back(tree.nodes[current].limiter);
      current = link.child;
      if (tree.nodes[current].level == 0) break;
    }
  }
  if (!tree.nodes[current].limiter.empty()) route.push_back(tree.nodes[current].limiter);
  return route;
}

}  // namespace pagecache::formats::simgrid
