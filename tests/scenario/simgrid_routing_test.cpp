// SimGrid's routing, per routing kind: each expected route is worked out by hand in a comment
// from SimGrid's rules (NetZoneImpl::get_global_route and get_bypass_route, FullZone, FloydZone,
// DijkstraZone, StarZone, EmptyZone), on small platforms written here and on SimGrid's own
// example platforms (inputs/simgrid/).

#include "formats/simgrid/routing/platform.hpp"

#include "import_property.hpp"
#include "support/files.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <thread>

using namespace pagecache;
using namespace pagecache::formats::simgrid;
using Catch::Contains;
using Strings = std::vector<std::string>;

namespace {

std::string input_text(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(PAGECACHE_INPUTS_DIR) / relative;
  REQUIRE(std::filesystem::is_regular_file(path));
  return pagecache::testing::slurp(path);
}

SgPlatform reference(const std::string& relative) { return read_simgrid_platform(input_text(relative), relative); }

SgPlatform platform(const std::string& body) { return read_simgrid_platform("<platform version=\"4.1\">\n" + body + "</platform>\n", "p.xml"); }

std::string message_of(const std::string& body) {
  try {
    platform(body);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(read without error)";
}

Strings route(const SgPlatform& p, const std::string& a, const std::string& b) {
  const SgRoute* r = p.find_route(a, b);
  return r == nullptr ? Strings{"(none)"} : r->links;
}

// Links l1 ... l9, one link each.
const std::string kLinks = R"(<link id="l1" bandwidth="1GBps"/><link id="l2" bandwidth="1GBps"/><link id="l3" bandwidth="1GBps"/>
<link id="l4" bandwidth="1GBps"/><link id="l5" bandwidth="1GBps"/><link id="l6" bandwidth="1GBps"/>
<link id="l7" bandwidth="1GBps"/><link id="l8" bandwidth="1GBps"/><link id="l9" bandwidth="1GBps"/>
)";

// Hosts A and B, routers X then Y (vertices 0, 1, 2, 3 of the zone), routes declared in the
// order A-Y, Y-B, A-X, X-B (one link each) and A-B direct over three links.
std::string two_ways(const std::string& routing) {
  return "<zone id=\"z\" routing=\"" + routing + "\">" + kLinks + R"(
<host id="A" speed="1Gf"/><host id="B" speed="1Gf"/><router id="X"/><router id="Y"/>
<route src="A" dst="Y"><link_ctn id="l3"/></route>
<route src="Y" dst="B"><link_ctn id="l4"/></route>
<route src="A" dst="X"><link_ctn id="l1"/></route>
<route src="X" dst="B"><link_ctn id="l2"/></route>
<route src="A" dst="B"><link_ctn id="l7"/><link_ctn id="l8"/><link_ctn id="l9"/></route>
</zone>)";
}

}  // namespace

TEST_CASE("Full routing takes the declared route only: through routers nothing is composed", "[scenario][simgrid][routing]") {
  // Tremblay -> Fafard is declared (links 4 3 2 0 1 8); the routes through the routers R.*
  // are declared too, but a Full zone never chains them.
  const SgPlatform p = reference("simgrid/small_platform_with_routers.xml");
  CHECK(p.routers.size() == 6);
  CHECK(route(p, "Tremblay", "Fafard") == Strings{"4", "3", "2", "0", "1", "8"});
  CHECK(route(p, "Fafard", "Tremblay") == Strings{"8", "1", "0", "2", "3", "4"});
  const SgPlatform q = platform("<zone id=\"z\" routing=\"Full\">" + kLinks + R"(<host id="A" speed="1Gf"/><host id="B" speed="1Gf"/><router id="X"/>
<route src="A" dst="X"><link_ctn id="l1"/></route><route src="X" dst="B"><link_ctn id="l2"/></route></zone>)");
  CHECK(route(q, "A", "B") == Strings{"(none)"});
}

TEST_CASE("Floyd routing: the fewest links over the declared routes, ties to the lowest intermediate vertex", "[scenario][simgrid][routing]") {
  // The direct route weighs 3 (links), A-X-B and A-Y-B weigh 2. Floyd relaxes through vertex
  // c = 0, 1, 2 (X), 3 (Y) in turn, replacing only on a strictly lower cost: X (vertex 2)
  // sets A -> B to 2 first, Y then ties and changes nothing. A -> B = l1 l2; back, through X
  // too, reversed: l2 l1.
  const SgPlatform p = platform(two_ways("Floyd"));
  CHECK(route(p, "A", "B") == Strings{"l1", "l2"});
  CHECK(route(p, "B", "A") == Strings{"l2", "l1"});
  // No route to itself declared: SimGrid gives the network's loopback, pcsim none.
  CHECK(route(p, "A", "A") == Strings{"(none)"});
}

TEST_CASE("Dijkstra routing: the fewest links, ties to the vertex met first in the declared routes", "[scenario][simgrid][routing]") {
  // Graph ids in order of first appearance in the routes: A 0, Y 1, B 2, X 3. From A, Y and X
  // both cost 1; the queue takes (1, Y=1) before (1, X=3), so Y reaches B first at cost 2 and
  // X's equal cost does not replace it: A -> B = l3 l4. Back from B: B's neighbours Y (id 1)
  // and X (id 3) at cost 1, Y first again: B -> A = l4 l3.
  for (const char* routing : {"Dijkstra", "DijkstraCache"}) {
    INFO(routing);
    const SgPlatform p = platform(two_ways(routing));
    CHECK(route(p, "A", "B") == Strings{"l3", "l4"});
    CHECK(route(p, "B", "A") == Strings{"l4", "l3"});
    CHECK(route(p, "A", "A") == Strings{"(none)"});
  }
}

TEST_CASE("a route weighs its links, not one hop: a direct route of three links loses to two of one", "[scenario][simgrid][routing]") {
  // Only A-X (1 link), X-B (1 link) and A-B (3 links): A -> B = l1 l2 for both algorithms.
  const std::string body = "<zone id=\"z\" routing=\"ROUTING\">" + kLinks + R"(<host id="A" speed="1Gf"/><host id="B" speed="1Gf"/><router id="X"/>
<route src="A" dst="B"><link_ctn id="l7"/><link_ctn id="l8"/><link_ctn id="l9"/></route>
<route src="A" dst="X"><link_ctn id="l1"/></route><route src="X" dst="B"><link_ctn id="l2"/></route></zone>)";
  for (const std::string routing : {"Floyd", "Dijkstra"}) {
    std::string text = body;
    text.replace(text.find("ROUTING"), 7, routing);
    CHECK(route(platform(text), "A", "B") == Strings{"l1", "l2"});
  }
}

TEST_CASE("routes between zones go through their gateways, found recursively down the zone tree", "[scenario][simgrid][routing]") {
  // root { A { A1 { a, ra1 }, A2 { x, rx }, A1 -> A2 via ra1 -> rx [l2] }, B { b }, A -> B via rx -> b [l3] }.
  // a -> b: the common ancestor is root, whose route A -> B is l3 from rx. a -> rx: common
  // ancestor A, route A1 -> A2 is l2 from ra1; a -> ra1 is A1's l1. b is the gateway itself.
  // So a -> b = l1 l2 l3; b -> a the same backwards (each route symmetrical): l3 l2 l1.
  const SgPlatform p = platform("<zone id=\"root\" routing=\"Full\">" + kLinks + R"(
<zone id="A" routing="Full">
  <zone id="A1" routing="Full"><host id="a" speed="1Gf"/><router id="ra1"/><route src="a" dst="ra1"><link_ctn id="l1"/></route></zone>
  <zone id="A2" routing="Full"><host id="x" speed="1Gf"/><router id="rx"/><route src="x" dst="rx"><link_ctn id="l4"/></route></zone>
  <zoneRoute src="A1" dst="A2" gw_src="ra1" gw_dst="rx"><link_ctn id="l2"/></zoneRoute>
</zone>
<zone id="B" routing="Full"><host id="b" speed="1Gf"/></zone>
<zoneRoute src="A" dst="B" gw_src="rx" gw_dst="b"><link_ctn id="l3"/></zoneRoute>
</zone>)");
  CHECK(route(p, "a", "b") == Strings{"l1", "l2", "l3"});
  CHECK(route(p, "b", "a") == Strings{"l3", "l2", "l1"});
  // x -> b: root's route from rx, x -> rx is A2's l4: l4 l3.
  CHECK(route(p, "x", "b") == Strings{"l4", "l3"});
  // a -> x: A's route A1 -> A2 (l2) between l1 (a -> ra1) and l4 backwards (rx -> x).
  CHECK(route(p, "a", "x") == Strings{"l1", "l2", "l4"});
}

TEST_CASE("<ASroute> is <zoneRoute>'s older name, and a one-way zoneRoute has no way back", "[scenario][simgrid][routing]") {
  const SgPlatform p = platform("<zone id=\"root\" routing=\"Full\">" + kLinks + R"(
<zone id="P" routing="Full"><host id="p" speed="1Gf"/></zone><zone id="Q" routing="Full"><host id="q" speed="1Gf"/></zone>
<ASroute src="P" dst="Q" gw_src="p" gw_dst="q" symmetrical="NO"><link_ctn id="l5"/></ASroute></zone>)");
  CHECK(route(p, "p", "q") == Strings{"l5"});
  CHECK(route(p, "q", "p") == Strings{"(none)"});
}

TEST_CASE("SimGrid's bypassRoute.xml: Dijkstra between zones, Floyd within one, a one-way bypass first", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/bypassRoute.xml");
  // The bypass is declared for AS_2_host1 -> AS_2_host2 only, and taken before Floyd.
  CHECK(route(p, "AS_2_host1", "AS_2_host2") == Strings{"AS_2_link7", "AS_2_link6", "AS_2_link5"});
  // Back, Floyd: host2 - central_router - host1 weighs 2, host2 - bypass_router1 - bypass_router2 - host1 3.
  CHECK(route(p, "AS_2_host2", "AS_2_host1") == Strings{"AS_2_link2", "AS_2_link1"});
  // AS_Big (Dijkstra) routes AS_1 -> AS_2 over backbone from AS_1_gateway to AS_2_gateway;
  // AS_1_host1 -> AS_1_gateway is AS_1_link (Full), AS_2_gateway -> AS_2_host1 is Floyd's
  // gateway - central_router - host1: link4 link1.
  CHECK(route(p, "AS_1_host1", "AS_2_host1") == Strings{"AS_1_link", "backbone", "AS_2_link4", "AS_2_link1"});
  CHECK(route(p, "AS_2_host1", "AS_1_host1") == Strings{"AS_2_link1", "AS_2_link4", "backbone", "AS_1_link"});
  CHECK(route(p, "AS_2_host3", "AS_1_host1") == Strings{"AS_2_link3", "AS_2_link4", "backbone", "AS_1_link"});
}

TEST_CASE("a bypassZoneRoute between two zones replaces their zoneRoute, gateways and all", "[scenario][simgrid][routing]") {
  // root's zoneRoute P -> Q goes r1 -> r2 over l5; the bypass P -> Q goes r1b -> r2 over l6.
  // h1 -> h2: no bypass between the hosts in root; up from them, P and Q at level 0 match the
  // bypass: h1 -> r1b (P's l2), l6, r2 -> h2 (Q's l3 backwards).
  const SgPlatform p = platform("<zone id=\"root\" routing=\"Full\">" + kLinks + R"(
<zone id="P" routing="Full"><host id="h1" speed="1Gf"/><router id="r1"/><router id="r1b"/>
  <route src="h1" dst="r1"><link_ctn id="l1"/></route><route src="h1" dst="r1b"><link_ctn id="l2"/></route></zone>
<zone id="Q" routing="Full"><host id="h2" speed="1Gf"/><router id="r2"/><route src="h2" dst="r2"><link_ctn id="l3"/></route></zone>
<zoneRoute src="P" dst="Q" gw_src="r1" gw_dst="r2"><link_ctn id="l5"/></zoneRoute>
<bypassZoneRoute src="P" dst="Q" gw_src="r1b" gw_dst="r2"><link_ctn id="l6"/></bypassZoneRoute>
</zone>)");
  CHECK(route(p, "h1", "h2") == Strings{"l2", "l6", "l3"});
  // The bypass is one way: back, the zoneRoute's reverse: l3 l5 l1.
  CHECK(route(p, "h2", "h1") == Strings{"l3", "l5", "l1"});
}

TEST_CASE("a None zone has no routes inside; its hosts are reached as gateways", "[scenario][simgrid][routing]") {
  // EmptyZone gives no link: n1 -> n2 has none. n1 as gw of zone N: n1 -> f is the zoneRoute's l5
  // then f's own zone F: f is its gateway. n2 -> f: N's route n2 -> n1 is empty, then l5.
  const SgPlatform p = platform("<zone id=\"root\" routing=\"Full\">" + kLinks + R"(
<zone id="N" routing="None"><host id="n1" speed="1Gf"/><host id="n2" speed="1Gf"/></zone>
<zone id="F" routing="Full"><host id="f" speed="1Gf"/></zone>
<zoneRoute src="N" dst="F" gw_src="n1" gw_dst="f"><link_ctn id="l5"/></zoneRoute></zone>)");
  CHECK(route(p, "n1", "n2") == Strings{"(none)"});
  CHECK(route(p, "n1", "f") == Strings{"l5"});
  CHECK(route(p, "n2", "f") == Strings{"l5"});
  CHECK_THAT(message_of(R"(<zone id="N" routing="None"><link id="l" bandwidth="1Bps"/><host id="a" speed="1Gf"/><host id="b" speed="1Gf"/>
<route src="a" dst="b"><link_ctn id="l"/></route></zone>)"),
             Contains("a zone with routing=\"None\" has no routes"));
}

TEST_CASE("SimGrid's cluster_multi.xml: clusters are zones whose routers are the gateways of zoneRoutes", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/cluster_multi.xml");
  // Each <cluster> gets the router prefix + id + "_router" + suffix, after its hosts.
  CHECK(p.find_host("node-simple_router.1core.org") == nullptr);
  REQUIRE(p.routers.size() >= 3);
  CHECK(p.routers[0].id == "node-simple_router.1core.org");
  // node-0.1core.org -> node-1.2cores.org: world's zoneRoute simple -> backboned is the FATPIPE
  // backbone, from simple's router to backboned's. Up to a router is the node's way up alone
  // (simple has no backbone: simple_link_0_UP); down from backboned's router is its backbone
  // then the node's link down.
  CHECK(route(p, "node-0.1core.org", "node-1.2cores.org") ==
        Strings{"simple_link_0_UP", "backbone", "backboned_backbone", "backboned_link_1_DOWN"});
  // Within a cluster, the star as before: up, backbone, down.
  CHECK(route(p, "node-0.2cores.org", "node-3.2cores.org") == Strings{"backboned_link_0_UP", "backboned_backbone", "backboned_link_3_DOWN"});
}

TEST_CASE("a Cluster zone routes through its host_links and backbone, and cabinets make host_links", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/routing_cluster.xml");
  // host1's way up is l1_UP then backbone1; host3's way down is backbone1 then l3 (one link both ways).
  CHECK(route(p, "host1", "host3") == Strings{"l1_UP", "backbone1", "l3"});
  CHECK(route(p, "host2", "host1") == Strings{"l2_UP", "backbone1", "l1_DOWN"});
  // host1 -> host4: AS0's zoneRoute my_cluster1 -> my_cluster2 (link1-2) from router1 to router2;
  // host1 -> router1 is host1's way up, router2 -> host4 host4's way down.
  CHECK(route(p, "host1", "host4") == Strings{"l1_UP", "backbone1", "link1-2", "backbone2", "l4_DOWN"});
  CHECK(route(p, "host6", "host2") == Strings{"l6", "backbone2", "link1-2", "backbone1", "l2_DOWN"});
  const SgPlatform m = reference("simgrid/meta_cluster.xml");
  // A cabinet's host H has links link_H_UP and link_H_DOWN.
  CHECK(m.hosts.size() == 60);
  CHECK(route(m, "host-1.cluster1", "host-12.cluster2") ==
        Strings{"link_host-1.cluster1_UP", "backbone1", "link1-2", "backbone2", "link_host-12.cluster2_DOWN"});
}

TEST_CASE("Vivaldi and Wifi zones and trace connections are refused; a trace alone is ignored with a warning", "[scenario][simgrid][routing]") {
  CHECK_THAT(message_of("<zone id=\"v\" routing=\"Vivaldi\"/>"), Contains("p.xml:2: <zone id=\"v\"> attribute routing: Vivaldi is refused"));
  CHECK_THAT(message_of("<zone id=\"w\" routing=\"Wifi\"/>"), Contains("p.xml:2: <zone id=\"w\"> attribute routing: Wifi is refused"));
  CHECK_THAT(message_of("<zone id=\"z\" routing=\"Full\"><host id=\"a\" speed=\"1Gf\" speed_file=\"s.txt\"/></zone>"),
             Contains("<host id=\"a\"> attribute speed_file: not supported"));
  const SgPlatform p = platform("<zone id=\"z\" routing=\"Full\">\n<trace id=\"t\" periodicity=\"1\">0 1\n</trace></zone>");
  REQUIRE(p.warnings.size() == 1);
  CHECK_THAT(p.warnings[0], Contains("p.xml:3: <trace id=\"t\">: ignored: a profile changes nothing until connected"));
}

TEST_CASE("what SimGrid refuses of routes between zones is refused naming the attribute", "[scenario][simgrid][routing]") {
  const std::string zones = R"(<zone id="root" routing="Full"><link id="l" bandwidth="1Bps"/>
<zone id="P" routing="Full"><host id="p" speed="1Gf"/></zone><zone id="Q" routing="Full"><host id="q" speed="1Gf"/></zone>
)";
  CHECK_THAT(message_of(zones + "<zoneRoute src=\"P\" dst=\"Q\" gw_src=\"q\" gw_dst=\"q\"><link_ctn id=\"l\"/></zoneRoute></zone>"),
             Contains("attribute gw_src: 'q' is not inside zone 'P'"));
  CHECK_THAT(message_of(zones + "<zoneRoute src=\"p\" dst=\"Q\" gw_src=\"p\" gw_dst=\"q\"><link_ctn id=\"l\"/></zoneRoute></zone>"),
             Contains("attribute src: 'p' is not a zone declared before"));
  CHECK_THAT(message_of(zones + "<route src=\"p\" dst=\"q\"><link_ctn id=\"l\"/></route></zone>"),
             Contains("attribute src: host 'p' is in zone 'P', not in this route's zone 'root'"));
  CHECK_THAT(message_of(zones + "<zoneRoute src=\"P\" dst=\"Q\" gw_src=\"p\" gw_dst=\"q\"/></zone>"), Contains("a route between zones with no link"));
  CHECK_THAT(message_of(zones + "<router id=\"p\"/></zone>"), Contains("attribute id: 'p' is already the name of a host"));
}

TEST_CASE("routed platforms keep the platform contract: find_route agrees with every route listed", "[scenario][simgrid][routing][fuzz]") {
  for (const char* file : {"bypassRoute.xml", "routing_cluster.xml", "meta_cluster.xml", "cluster_multi.xml", "small_platform_with_routers.xml",
                           "cluster_torus.xml", "cluster_fat_tree.xml"}) {
    INFO(file);
    CHECK(fuzz::check_platform_text(input_text(std::string("simgrid/") + file), file).empty());
  }
  CHECK(fuzz::check_platform_text("<platform version=\"4.1\">" + two_ways("Floyd") + "</platform>", "f.xml").empty());
  CHECK(fuzz::check_platform_text("<platform version=\"4.1\">" + two_ways("Dijkstra") + "</platform>", "d.xml").empty());
}

TEST_CASE("SimGrid's cluster_torus.xml: dimension-order routing, right within half the ring, else left", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/cluster_torus.xml");
  // Dimensions 3, 2, 2: node r has coordinates (r % 3, r / 3 % 2, r / 6). Node r's link in
  // dimension j goes to the next rank in that ring: bob_cluster_link_from_r_to_n.
  CHECK(p.hosts.size() == 12);
  CHECK(p.find_link("bob_cluster_link_from_2_to_0_UP") != nullptr);   // the ring of dimension 0 wraps
  CHECK(p.find_link("bob_cluster_link_from_4_to_1_DOWN") != nullptr); // rank 4 is last of dimension 1's ring
  // 0 -> 4 = (1, 1, 0): dimension 0 first, target 1 is within 3 / 2 = 1 on the right: up link
  // 0 -> 1; then dimension 1, 0 -> 1 on the right again: 1 -> 4.
  CHECK(route(p, "node-0.simgrid.org", "node-4.simgrid.org") == Strings{"bob_cluster_link_from_0_to_1_UP", "bob_cluster_link_from_1_to_4_UP"});
  // 0 -> 2: target 2 is not within 1 on the right of 0: left, wrapping to 2, over 2's link to
  // 0 taken down.
  CHECK(route(p, "node-0.simgrid.org", "node-2.simgrid.org") == Strings{"bob_cluster_link_from_2_to_0_DOWN"});
  // A node to itself: its loopback (loopback_bw given).
  CHECK(route(p, "node-7.simgrid.org", "node-7.simgrid.org") == Strings{"bob_cluster_link_7_loopback"});
}

TEST_CASE("SimGrid's cluster_fat_tree.xml: d-mod-k up to a common ancestor, then down by label", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/cluster_fat_tree.xml");
  // "2;4,4;1,2;1,2": 16 nodes, 4 switches at level 1 (ids 31, 30, 29, 28: numbered down from
  // 32), 2 at level 2 (27, 26). Node n has label (n % 4, n / 4) and one link to switch 31 - n / 4
  // (link_from_<n>_<switch>_<n>); each level-1 switch has two links to each of 27 and 26,
  // switch 31's numbered 16, 17 (to 27) and 18, 19 (to 26), switch 30's 20 to 23.
  CHECK(p.hosts.size() == 16);
  CHECK(p.find_link("link_from_31_26_19_DOWN") != nullptr);
  // 0 -> 1: switch 31 holds both: up, then down to the child whose label digit 0 is 1.
  CHECK(route(p, "node-0.simgrid.org", "node-1.simgrid.org") == Strings{"link_from_0_31_0_UP", "link_from_1_31_1_DOWN"});
  // 0 -> 4 (label (0, 1)): up to 31; 31 does not hold 4: d = 4 mod (2 parents x 2 links) = 0,
  // port 0 is link 16 to 27. Down from 27: ports scanned from 0, the first whose number mod 4
  // is 4's digit 1 is port 1, switch 30's link 20; then 30's port 0, node 4.
  CHECK(route(p, "node-0.simgrid.org", "node-4.simgrid.org") ==
        Strings{"link_from_0_31_0_UP", "link_from_31_27_16_UP", "link_from_30_27_20_DOWN", "link_from_4_30_4_DOWN"});
  // 0 -> 5: the destination's position picks the port up: 5 mod 4 = 1, switch 31's port 1 is
  // its first link to 26 (18). Down from 26: port 1 (5's digit 1) is switch 30's link 22, then
  // 30's port 1, node 5.
  CHECK(route(p, "node-0.simgrid.org", "node-5.simgrid.org") ==
        Strings{"link_from_0_31_0_UP", "link_from_31_26_18_UP", "link_from_30_26_22_DOWN", "link_from_5_30_5_DOWN"});
}

TEST_CASE("SimGrid's cluster_dragonfly.xml: local, green, black and blue links with limiters", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/cluster_dragonfly.xml");
  // "3,4;4,3;5,1;2": 3 groups of 4 chassis of 5 blades (routers) of 2 nodes: 120 nodes, router
  // r = node / 2. Links are numbered in creation order: local ones 0-119 (router r, node k:
  // 2r + k), green 120-239, black 240-329, blue 330-332. Node n's limiter is named n; router
  // r's 239 - r (numbered down from 2 x 120).
  CHECK(p.hosts.size() == 120);
  CHECK(p.find_link("blue_link_between_group_0_and_1_routers_1_and_20_330_UP") != nullptr);
  CHECK(p.find_link("blue_link_between_group_0_and_1_routers_1_and_20_330_UP")->bandwidth == 4 * 125e6);  // 4 blue links
  // 0 -> 2 (router 1, same chassis): green from blade 0 to blade 1, the routers' limiters around it.
  CHECK(route(p, "node-0.simgrid.org", "node-2.simgrid.org") ==
        Strings{"bob_cluster_link_0_limiter", "local_link_from_router_0_to_node_0_0_UP", "bob_cluster_link_239_limiter",
                "green_link_in_chassis_0_between_routers_0_and_1_120_UP", "bob_cluster_link_238_limiter",
                "local_link_from_router_1_to_node_0_2_DOWN", "bob_cluster_link_2_limiter"});
  // 0 -> 40 (group 1, router 20): green to the blade numbered as the target group (1), which
  // is in chassis 0 already; its blue link to group 1 arrives at router 20 = the target's.
  CHECK(route(p, "node-0.simgrid.org", "node-40.simgrid.org") ==
        Strings{"bob_cluster_link_0_limiter", "local_link_from_router_0_to_node_0_0_UP", "bob_cluster_link_239_limiter",
                "green_link_in_chassis_0_between_routers_0_and_1_120_UP", "blue_link_between_group_0_and_1_routers_1_and_20_330_UP",
                "bob_cluster_link_238_limiter", "bob_cluster_link_219_limiter", "local_link_from_router_20_to_node_0_40_DOWN",
                "bob_cluster_link_40_limiter"});
  CHECK(route(p, "node-5.simgrid.org", "node-5.simgrid.org") == Strings{"bob_cluster_link_5_loopback"});
}

TEST_CASE("a topology's parameters are checked, naming the attribute", "[scenario][simgrid][routing]") {
  const std::string cluster = R"(<cluster id="c" prefix="n" suffix="" radical="0-7" speed="1Gf" bw="1GBps" lat="0" )";
  CHECK_THAT(message_of(cluster + "topology=\"FAT_TREE\" topo_parameters=\"2;4,4;1,2\"/>"), Contains("attribute topo_parameters: a fat tree is"));
  CHECK_THAT(message_of(cluster + "topology=\"TORUS\" topo_parameters=\"3,0\"/>"), Contains("attribute topo_parameters: '0' is not a whole number"));
  CHECK_THAT(message_of(cluster + "topology=\"TORUS\" topo_parameters=\"3,3\"/>"), Contains("attribute radical: 8 nodes for a topology of 9"));
  CHECK_THAT(message_of(cluster + "topology=\"DRAGONFLY\" topo_parameters=\"1,1;1,1;1\"/>"), Contains("attribute topo_parameters: a dragonfly is"));
  // A few numbers may ask for 10^12 switches and links: refused before anything is built.
  CHECK_THAT(message_of(R"(<cluster id="c" prefix="n" suffix="" radical="0-3" speed="1Gf" bw="1GBps" lat="0" topology="FAT_TREE" )"
                        R"(topo_parameters="2;2,2;1000000,1000000;1000,1"/>)"),
             Contains("attribute topo_parameters: 2.004e+12 links and switches, more than the 1.6e+06 pcsim takes"));
}

TEST_CASE("the platform fuzzer's contract holds on the reference platforms and its seeds, which read within its bounds",
          "[scenario][simgrid][fuzz]") {
  std::vector<std::string> files;
  for (const char* name : {"wrench-cache/single_host.xml", "wrench-cache/two_hosts.xml"}) files.push_back(std::string(PAGECACHE_INPUTS_DIR) + "/" + name);
  for (const auto& entry : std::filesystem::directory_iterator(std::string(PAGECACHE_INPUTS_DIR) + "/simgrid")) {
    if (entry.path().extension() == ".xml") files.push_back(entry.path().string());
  }
  for (const auto& entry : std::filesystem::directory_iterator(PAGECACHE_FUZZ_SEEDS_DIR)) {
    if (entry.path().extension() == ".xml") files.push_back(entry.path().string());
  }
  REQUIRE(files.size() >= 21);
  std::size_t small = 0;
  for (const std::string& path : files) {
    INFO(path);
    const std::string text = pagecache::testing::slurp(path);
    CHECK(fuzz::check_platform_text(text, path).empty());
    // Under the fuzzer's bounds (30 hosts a cluster, 100 in all) a platform reads, or is
    // refused for its size; one that reads keeps the import contract too (show reads back).
    if (fuzz::reads_as_small_platform(text)) {
      ++small;
      CHECK_FALSE(read_simgrid_platform(text, path, fuzz::fuzz_platform_limits()).hosts.empty());
      CHECK(fuzz::check_platform_import(text).empty());
    } else {
      CHECK_THROWS_WITH(read_simgrid_platform(text, path, fuzz::fuzz_platform_limits()), Contains("attribute radical") || Contains("more than 100 hosts"));
    }
  }
  CHECK(small >= 15);
  // Broken inputs keep it too: refused with FILE:LINE.
  CHECK(fuzz::check_platform_text("<platform version=\"4.1\"><zone id=\"z\" routing=\"Vivaldi\"/></platform>", "x.xml").empty());
  CHECK(fuzz::check_platform_text("\xff\xfe<", "x.xml").empty());
}

TEST_CASE("routes through zones are found from several threads at once, each the same as alone", "[scenario][simgrid][routing]") {
  const SgPlatform p = reference("simgrid/bypassRoute.xml");
  const SgPlatform q = reference("simgrid/cluster_fat_tree.xml");
  // Alone first, on copies, which share no routes built: the expected answers.
  const SgPlatform p_alone = reference("simgrid/bypassRoute.xml");
  const SgPlatform q_alone = reference("simgrid/cluster_fat_tree.xml");
  std::vector<std::thread> threads;
  std::vector<int> wrong(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 50; ++round) {
        for (const SgHost& a : p.hosts) {
          for (const SgHost& b : p.hosts) wrong[t] += route(p, a.id, b.id) != route(p_alone, a.id, b.id);
        }
        const std::string a = q.hosts[static_cast<std::size_t>(round + t) % 16].id, b = q.hosts[static_cast<std::size_t>(3 * round) % 16].id;
        wrong[t] += route(q, a, b) != route(q_alone, a, b);
      }
    });
  }
  for (std::thread& t : threads) t.join();
  CHECK(wrong == std::vector<int>(4, 0));
}
