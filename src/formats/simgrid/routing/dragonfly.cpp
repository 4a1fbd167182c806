// A DRAGONFLY cluster as SimGrid's DragonflyZone builds it (a router per blade of each chassis
// of each group; local links to its nodes, green links between the blades of a chassis, black
// between the chassis of a group, blue between groups) and routes it.

#include "formats/simgrid/routing/topology.hpp"

namespace pagecache::formats::simgrid {

namespace {

struct Shape {
  unsigned groups, blue, chassis, black, blades, green, nodes;
};

Shape shape_of(const SgCluster& c) {
  const std::vector<unsigned>& p = c.topology_parameters;
  return {p.at(0), p.at(1), p.at(2), p.at(3), p.at(4), p.at(5), p.at(6)};
}

}  // namespace

SgDragonfly sg_dragonfly(const SgCluster& c) {
  const Shape s = shape_of(c);
  const bool split = c.split_duplex;
  SgDragonfly fly;
  // Routers' limiters are numbered down from twice the nodes.
  std::size_t number = 2 * c.size();
  for (unsigned i = 0; i < s.groups; ++i) {
    for (unsigned j = 0; j < s.chassis; ++j) {
      for (unsigned k = 0; k < s.blades; ++k) {
        SgDragonfly::Router r;
        r.group = i, r.chassis = j, r.blade = k;
        if (c.limiter) r.limiter = c.id + "_link_" + std::to_string(--number) + "_limiter";
        fly.routers.push_back(std::move(r));
      }
    }
  }
  std::size_t serial = c.link_serial;
  // A link of `count` links: its up and down halves, or one link for both.
  const auto make = [&](const std::string& id, unsigned count) {
    const std::string named = id + "_" + std::to_string(serial++);
    if (split) {
      fly.links.push_back({named + "_UP", SgTopologyLink::Kind::Private, static_cast<double>(count)});
      fly.links.push_back({named + "_DOWN", SgTopologyLink::Kind::Private, static_cast<double>(count)});
      return std::pair{named + "_UP", named + "_DOWN"};
    }
    fly.links.push_back({named, SgTopologyLink::Kind::Private, static_cast<double>(count)});
    return std::pair{named, named};
  };
  for (std::size_t r = 0; r < fly.routers.size(); ++r) {
    fly.routers[r].green.resize(s.blades);
    fly.routers[r].black.resize(s.chassis);
    for (unsigned n = 0; n < s.nodes; ++n) {
      const auto [up, down] = make("local_link_from_router_" + std::to_string(r) + "_to_node_" + std::to_string(n), 1);
      fly.routers[r].local.push_back(up);
      if (split) fly.routers[r].local.push_back(down);
    }
  }
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.groups) * s.chassis; ++i) {
    for (unsigned j = 0; j < s.blades; ++j) {
      for (unsigned k = j + 1; k < s.blades; ++k) {
        const auto [up, down] = make("green_link_in_chassis_" + std::to_string(i % s.chassis) + "_between_routers_" + std::to_string(j) + "_and_" + std::to_string(k), s.green);
        fly.routers[i * s.blades + j].green[k] = up;
        fly.routers[i * s.blades + k].green[j] = down;
      }
    }
  }
  const std::size_t per_group = static_cast<std::size_t>(s.blades) * s.chassis;
  for (unsigned i = 0; i < s.groups; ++i) {
    for (unsigned j = 0; j < s.chassis; ++j) {
      for (unsigned k = j + 1; k < s.chassis; ++k) {
        for (unsigned l = 0; l < s.blades; ++l) {
          const auto [up, down] = make("black_link_in_group_" + std::to_string(i) + "_between_chassis_" + std::to_string(j) + "_and_" + std::to_string(k) +
                                           "_blade_" + std::to_string(l),
                                       s.black);
          fly.routers[i * per_group + j * s.blades + l].black[k] = up;
          fly.routers[i * per_group + k * s.blades + l].black[j] = down;
        }
      }
    }
  }
  for (unsigned i = 0; i < s.groups; ++i) {
    for (unsigned j = i + 1; j < s.groups; ++j) {
      const std::size_t from = i * per_group + j, to = j * per_group + i;
      const auto [up, down] = make("blue_link_between_group_" + std::to_string(i) + "_and_" + std::to_string(j) + "_routers_" + std::to_string(from) + "_and_" + std::to_string(to), s.blue);
      // SimGrid keeps one blue link per router: a later one replaces an earlier.
      if (from < fly.routers.size()) fly.routers[from].blue = up;
      if (to < fly.routers.size()) fly.routers[to].blue = down;
    }
  }
  return fly;
}

std::vector<std::string> sg_dragonfly_route(const SgCluster& c, const SgDragonfly& fly, std::size_t from, std::size_t to) {
  const Shape s = shape_of(c);
  if (from == to && c.loopback) return {c.id + "_link_" + std::to_string(c.radicals.at(from)) + "_loopback"};
  const std::size_t per_group = static_cast<std::size_t>(s.blades) * s.chassis;
  const std::size_t per_router = s.nodes;
  const auto router_of = [&](std::size_t node) { return node / per_router; };
  const std::size_t mine = router_of(from), target = router_of(to);
  const SgDragonfly::Router& target_router = fly.routers[target];
  const unsigned target_group = static_cast<unsigned>(to / (per_group * per_router));
  const unsigned my_group = static_cast<unsigned>(from / (per_group * per_router));
  const unsigned my_chassis = static_cast<unsigned>((from % (per_group * per_router)) / (static_cast<std::size_t>(s.blades) * per_router));
  const unsigned width = c.split_duplex ? 2 : 1;
  std::vector<std::string> route;
  bool missing = false;
  const auto add = [&](const std::string& link) {
    missing = missing || link.empty();
    route.push_back(link);
  };
  const auto limiter = [&](std::size_t r) {
    if (!fly.routers[r].limiter.empty()) route.push_back(fly.routers[r].limiter);
  };
  if (c.limiter) route.push_back(c.id + "_link_" + std::to_string(from) + "_limiter");
  add(fly.routers[mine].local.at((from % per_router) * width));
  std::size_t current = mine;
  if (target != mine) {
    if (target_router.group != fly.routers[current].group) {
      // To the router of this chassis whose blade is the target's group, to chassis 0, then blue.
      if (fly.routers[current].blade != target_group) {
        if (target_group >= s.blades) return {};
        limiter(current);
        add(fly.routers[current].green[target_group]);
        current = my_group * per_group + my_chassis * s.blades + target_group;
      }
      if (fly.routers[current].chassis != 0) {
        limiter(current);
        add(fly.routers[current].black[0]);
        current = my_group * per_group + target_group;
      }
      add(fly.routers[current].blue);
      limiter(current);
      current = target_group * per_group + my_group;
      if (current >= fly.routers.size()) return {};
    }
    if (target_router.blade != fly.routers[current].blade) {
      limiter(current);
      add(fly.routers[current].green[target_router.blade]);
      current = target_group * per_group + target_router.blade;
    }
    if (target_router.chassis != fly.routers[current].chassis) {
      limiter(current);
      add(fly.routers[current].black[target_router.chassis]);
    }
  }
  limiter(target);
  add(target_router.local.at((to % per_router) * width + width - 1));
  if (c.limiter) route.push_back(c.id + "_link_" + std::to_string(to) + "_limiter");
  return missing ? std::vector<std::string>{} : route;
}

}  // namespace pagecache::formats::simgrid
