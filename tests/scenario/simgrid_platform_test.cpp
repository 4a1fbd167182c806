// The SimGrid platform reader: SimGrid's units, the reference platforms as WRENCH and SimGrid
// ship them, clusters expanded as SimGrid expands them, and every refusal naming the file,
// line, element and attribute.

#include "formats/simgrid/routing/platform.hpp"
#include "formats/simgrid/xml/radical.hpp"
#include "formats/simgrid/xml/units.hpp"

#include "platform_property.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

using namespace pagecache;
using namespace pagecache::formats::simgrid;
using Catch::Contains;
using Strings = std::vector<std::string>;

namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string reference_text(const std::string& relative) { return file_text(std::string(PAGECACHE_INPUTS_DIR) + "/" + relative); }

SgPlatform reference(const std::string& relative) { return read_simgrid_platform(reference_text(relative), relative); }

// A version 4.1 platform of one Full zone holding `body`, which starts on line 3.
std::string in_zone(const std::string& body) {
  return "<?xml version='1.0'?>\n<platform version=\"4.1\"><zone id=\"z\" routing=\"Full\">\n" + body + "\n</zone></platform>\n";
}

std::string message_of(const std::string& text) {
  try {
    read_simgrid_platform(text, "bad.xml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kTwoHosts = "<host id=\"a\" speed=\"1Gf\"/>\n<host id=\"b\" speed=\"1Gf\"/>\n";

}  // namespace

// ---------------------------------------------------------------- units

TEST_CASE("SimGrid bandwidths are bytes per second with decimal and binary prefixes, and bits per second", "[scenario][simgrid]") {
  CHECK(parse_sg_bandwidth("125MBps") == 1.25e8);
  CHECK(parse_sg_bandwidth("1kBps") == 1e3);
  CHECK(parse_sg_bandwidth("3GBps") == 3e9);
  CHECK(parse_sg_bandwidth("1TBps") == 1e12);
  CHECK(parse_sg_bandwidth("1PBps") == 1e15);
  CHECK(parse_sg_bandwidth("1000EBps") == 1e21);
  CHECK(parse_sg_bandwidth("1KiBps") == 1024.0);
  CHECK(parse_sg_bandwidth("1MiBps") == 1048576.0);
  CHECK(parse_sg_bandwidth("2GiBps") == 2.0 * (1 << 30));
  CHECK(parse_sg_bandwidth("1EiBps") == std::ldexp(1.0, 60));
  // Bits: 1 Bps = 8 bps.
  CHECK(parse_sg_bandwidth("8bps") == 1.0);
  CHECK(parse_sg_bandwidth("1Mbps") == 125000.0);
  CHECK(parse_sg_bandwidth("10Gbps") == 1.25e9);
  CHECK(parse_sg_bandwidth("1Mibps") == 131072.0);
  CHECK(parse_sg_bandwidth("41.279125MBps") == 41.279125 * 1e6);
  // "KBps" is no SimGrid unit (k is the decimal prefix), nor is a space before the unit.
  CHECK_THROWS_WITH(parse_sg_bandwidth("1KBps"), Contains("unknown bandwidth unit 'KBps'"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("5 MBps"), Contains("no space between number and unit"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("5MB/s"), Contains("unknown bandwidth unit 'MB/s'"));
}

TEST_CASE("SimGrid times run from picoseconds to weeks", "[scenario][simgrid]") {
  CHECK(parse_sg_time("50us") == 50 / 1e6);
  CHECK(parse_sg_time("1.461517ms") == 1.461517 / 1e3);
  CHECK(parse_sg_time("3ns") == 3 / 1e9);
  CHECK(parse_sg_time("4ps") == 4 / 1e12);
  CHECK(parse_sg_time("2s") == 2.0);
  CHECK(parse_sg_time("2m") == 120.0);
  CHECK(parse_sg_time("2h") == 7200.0);
  CHECK(parse_sg_time("2d") == 172800.0);
  CHECK(parse_sg_time("1w") == 604800.0);
  CHECK_THROWS_WITH(parse_sg_time("2min"), Contains("unknown time unit 'min'"));
}

TEST_CASE("SimGrid speeds are flop/s with decimal prefixes only, abbreviated or spelt out", "[scenario][simgrid]") {
  CHECK(parse_sg_speed("1Gf") == 1e9);
  CHECK(parse_sg_speed("98.095Mf") == 98.095 * 1e6);
  CHECK(parse_sg_speed("3kf") == 3e3);
  CHECK(parse_sg_speed("1Tf") == 1e12);
  CHECK(parse_sg_speed("5flops") == 5.0);
  CHECK(parse_sg_speed("2gigaflops") == 2e9);
  CHECK(parse_sg_speed("1zetaflops") == 1e21);  // SimGrid's spelling
  CHECK_THROWS_WITH(parse_sg_speed("1Kif"), Contains("unknown speed unit 'Kif'"));
  CHECK_THROWS_WITH(parse_sg_speed("1Gflops"), Contains("unknown speed unit"));
  CHECK_THROWS_WITH(parse_sg_speed("1GF"), Contains("unknown speed unit"));
}

TEST_CASE("SimGrid sizes are bytes or bits with decimal and binary prefixes", "[scenario][simgrid]") {
  CHECK(parse_sg_size("268GB") == 268e9);
  CHECK(parse_sg_size("500GiB") == 500.0 * (1 << 30));
  CHECK(parse_sg_size("1KiB") == 1024.0);
  CHECK(parse_sg_size("3MB") == 3e6);
  CHECK(parse_sg_size("16b") == 2.0);
  CHECK(parse_sg_size("1kb") == 125.0);
  CHECK_THROWS_WITH(parse_sg_size("1GBps"), Contains("unknown size unit 'GBps'"));
}

TEST_CASE("a SimGrid value without unit is read in the base unit, and zero needs none", "[scenario][simgrid]") {
  CHECK(parse_sg_bandwidth("100") == 100.0);
  CHECK(parse_sg_time("0.5") == 0.5);
  CHECK(parse_sg_speed("1e9") == 1e9);
  CHECK(parse_sg_size("42") == 42.0);
  CHECK(sg_lacks_unit("100"));
  CHECK(sg_lacks_unit(" 2.5 "));
  CHECK_FALSE(sg_lacks_unit("0"));
  CHECK_FALSE(sg_lacks_unit("0.0"));
  CHECK_FALSE(sg_lacks_unit("100Bps"));
  CHECK(parse_sg_bandwidth(" 7Bps ") == 7.0);
}

TEST_CASE("SimGrid values that are negative, not finite, out of range or not numbers are refused", "[scenario][simgrid]") {
  CHECK_THROWS_WITH(parse_sg_bandwidth("-5MBps"), Contains("'-5MBps' is negative"));
  CHECK_THROWS_WITH(parse_sg_time("-1s"), Contains("negative"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("inf"), Contains("should start with a number"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("nanBps"), Contains("should start with a number"));
  CHECK_THROWS_WITH(parse_sg_speed("+1Gf"), Contains("should start with a number"));
  CHECK_THROWS_WITH(parse_sg_speed("Gf"), Contains("should start with a number"));
  CHECK_THROWS_WITH(parse_sg_bandwidth(""), Contains("empty bandwidth"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("0x10Bps"), Contains("unknown bandwidth unit 'x10Bps'"));
  CHECK_THROWS_WITH(parse_sg_time("1e400s"), Contains("out of range"));
  CHECK_THROWS_WITH(parse_sg_bandwidth("1e308EBps"), Contains("too large"));
  CHECK_THROWS_AS(parse_sg_size("12 GB"), ConfigError);
}

TEST_CASE("a cluster radical names numbers and ranges in order, within a bound checked before allocating", "[scenario][simgrid]") {
  CHECK(parse_sg_radical("0-3", 100) == std::vector<int>{0, 1, 2, 3});
  CHECK(parse_sg_radical("1,3,5-7", 100) == std::vector<int>{1, 3, 5, 6, 7});
  CHECK(parse_sg_radical("9, 007", 100) == std::vector<int>{9, 7});
  CHECK(parse_sg_radical("0-99", 100).size() == 100);
  CHECK_THROWS_WITH(parse_sg_radical("0-100", 100), Contains("names more than 100 hosts"));
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(parse_sg_radical("0-2147483647", 100'000), Contains("names more than 100000 hosts"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));  // not a timing figure: a hang guard
  CHECK_THROWS_WITH(parse_sg_radical("5-3", 100), Contains("runs backwards"));
  CHECK_THROWS_WITH(parse_sg_radical("1-2-3", 100), Contains("is not a number"));
  CHECK_THROWS_WITH(parse_sg_radical("a", 100), Contains("'a' is not a number"));
  CHECK_THROWS_WITH(parse_sg_radical("", 100), Contains("is not a number"));
  CHECK_THROWS_WITH(parse_sg_radical("1,", 100), Contains("is not a number"));
  CHECK_THROWS_WITH(parse_sg_radical("-1", 100), Contains("is not a number"));
  CHECK_THROWS_WITH(parse_sg_radical("99999999999", 100), Contains("is not a number"));
}

// ---------------------------------------------------------------- the reference platforms

TEST_CASE("WRENCH-cache's single host: a host with a memory disk and a local disk, and its loopback route", "[scenario][simgrid]") {
  const SgPlatform p = reference("wrench-cache/single_host.xml");
  CHECK(p.version == "4.1");
  CHECK(p.file == "wrench-cache/single_host.xml");
  REQUIRE(p.hosts.size() == 1);
  const SgHost& h = p.hosts[0];
  CHECK(h.id == "host01");
  CHECK(h.speed == 1e9);
  CHECK(h.cores == 32);
  CHECK(h.line == 5);
  CHECK(h.props == SgProps{{"ram", "268GB"}});
  REQUIRE(h.disks.size() == 2);
  CHECK(h.disks[0].id == "memory");
  CHECK(h.disks[0].read_bw == 4.812e9);
  CHECK(h.disks[0].write_bw == 4.812e9);
  CHECK(h.disks[0].props == SgProps{{"size", "268GB"}, {"mount", "/memory"}});
  CHECK(h.disks[0].line == 8);
  CHECK(h.disks[1].id == "disk01");
  CHECK(h.disks[1].read_bw == 4.65e8);
  CHECK(h.disks[1].props == SgProps{{"size", "450GB"}, {"mount", "/"}});
  CHECK(parse_sg_size(h.disks[1].props[0].second) == 450e9);
  REQUIRE(p.links.size() == 1);
  CHECK(p.links[0].id == "loopback");
  CHECK(p.links[0].bandwidth == 1e21);
  CHECK(p.links[0].latency == 0.0);
  CHECK(p.links[0].sharing == LinkSharing::Shared);
  REQUIRE(p.routes.size() == 1);
  CHECK(p.routes[0].src == "host01");
  CHECK(p.routes[0].dst == "host01");
  CHECK(p.routes[0].links == Strings{"loopback"});
  CHECK(p.routes[0].line == 21);
  CHECK(p.find_route("host01", "host01") == &p.routes[0]);
  CHECK(p.find_host("host01") == &p.hosts[0]);
  CHECK(p.find_host("host02") == nullptr);
  CHECK(p.find_link("loopback") == &p.links[0]);
  CHECK(p.warnings.empty());
}

TEST_CASE("WRENCH-cache's two hosts: one network link, used both ways, and a loopback each", "[scenario][simgrid]") {
  const SgPlatform p = reference("wrench-cache/two_hosts.xml");
  REQUIRE(p.hosts.size() == 2);
  CHECK(p.hosts[0].id == "compute_host");
  CHECK(p.hosts[1].id == "storage_host");
  CHECK(p.hosts[1].disks[1].read_bw == 4.45e8);
  CHECK(p.hosts[1].disks[1].props == SgProps{{"size", "400GB"}, {"mount", "/"}});
  const SgLink* net = p.find_link("network_link");
  REQUIRE(net != nullptr);
  CHECK(net->bandwidth == 3e9);
  CHECK(net->latency == 20 / 1e6);
  CHECK(net->line == 31);
  REQUIRE(p.routes.size() == 3);
  const SgRoute* there = p.find_route("storage_host", "compute_host");
  CHECK(there == &p.routes[0]);
  // Routes are symmetrical by default: the way back is built, oriented the way it was asked.
  const SgRoute* back = p.find_route("compute_host", "storage_host");
  REQUIRE(back != nullptr);
  CHECK(back->src == "compute_host");
  CHECK(back->dst == "storage_host");
  CHECK(back->links == Strings{"network_link"});
  CHECK(back->line == 38);
  CHECK(p.find_route("compute_host", "storage_host") == back);
  CHECK(p.find_route("compute_host", "compute_host")->links == Strings{"loopback_ComputeHost"});
  CHECK(p.find_route("storage_host", "storage_host")->links == Strings{"loopback_StorageHost"});
  CHECK(p.find_route("compute_host", "nowhere") == nullptr);
}

TEST_CASE("SimGrid's hosts with disks: read and write bandwidths apart, disk properties kept", "[scenario][simgrid]") {
  const SgPlatform p = reference("simgrid/hosts_with_disks.xml");
  REQUIRE(p.hosts.size() == 2);
  const SgHost* bob = p.find_host("bob");
  REQUIRE(bob != nullptr);
  CHECK(bob->cores == 1);
  REQUIRE(bob->disks.size() == 2);
  CHECK(bob->disks[0].id == "Disk1");
  CHECK(bob->disks[0].read_bw == 1e8);
  CHECK(bob->disks[0].write_bw == 4e7);
  CHECK(bob->disks[0].props ==
        SgProps{{"size", "500GiB"}, {"mount", "/scratch"}, {"content", "storage/content/storage_content.txt"}});
  CHECK(parse_sg_size(bob->disks[0].props[0].second) == 500.0 * (1 << 30));
  CHECK(bob->disks[1].id == "Disk2");
  CHECK(bob->disks[1].read_bw == 2e8);
  CHECK(bob->disks[1].write_bw == 8e7);
  CHECK(bob->disks[1].props.empty());
  const SgHost* alice = p.find_host("alice");
  REQUIRE(alice != nullptr);
  REQUIRE(alice->disks.size() == 1);
  CHECK(alice->disks[0].id == "Disk1");  // disk ids are per host
  CHECK(p.find_link("link1")->bandwidth == 1.25e8);
  CHECK(p.find_link("link1")->latency == 150 / 1e6);
  CHECK(p.find_route("alice", "bob")->links == Strings{"link1"});
  CHECK(p.find_route("alice", "alice") == nullptr);  // none declared
}

TEST_CASE("SimGrid's small platform, version 4 with <AS>: five hosts, eleven links, fifteen routes", "[scenario][simgrid]") {
  const SgPlatform p = reference("simgrid/small_platform.xml");
  CHECK(p.version == "4");
  REQUIRE(p.hosts.size() == 5);
  CHECK(p.hosts[0].id == "Tremblay");
  CHECK(p.hosts[0].speed == 98.095 * 1e6);
  CHECK(p.hosts[0].line == 8);
  CHECK(p.hosts[4].id == "Bourassa");
  CHECK(p.hosts[4].speed == 48.492 * 1e6);
  REQUIRE(p.links.size() == 11);
  CHECK(p.links[0].id == "6");
  CHECK(p.links[3].id == "9");
  CHECK(p.links[3].latency == 1.461517 / 1e3);
  const SgLink* loopback = p.find_link("loopback");
  REQUIRE(loopback != nullptr);
  CHECK(loopback->sharing == LinkSharing::Fatpipe);
  CHECK(loopback->bandwidth == 498e6);
  CHECK(loopback->latency == 15 / 1e6);
  REQUIRE(p.routes.size() == 15);
  CHECK(p.find_route("Tremblay", "Fafard")->links == Strings{"4", "3", "2", "0", "1", "8"});
  CHECK(p.find_route("Fafard", "Tremblay")->links == Strings{"8", "1", "0", "2", "3", "4"});
  CHECK(p.find_route("Bourassa", "Ginette")->links == Strings{"7", "6", "1", "0", "2", "5"});
  CHECK(p.find_route("Jupiter", "Jupiter")->links == Strings{"loopback"});
  std::size_t count = 0;
  p.for_each_route([&](const SgRoute&) { ++count; });
  CHECK(count == 15);
  CHECK(p.warnings.empty());
}

TEST_CASE("SimGrid's cluster with a backbone: 100 nodes, split-duplex private links, routes up, across and down", "[scenario][simgrid]") {
  const SgPlatform p = reference("simgrid/cluster_backbone.xml");
  REQUIRE(p.hosts.size() == 100);
  CHECK(p.hosts[0].id == "node-0.acme.org");
  CHECK(p.hosts[99].id == "node-99.acme.org");
  CHECK(p.hosts[42].speed == 1e9);
  CHECK(p.hosts[42].cluster == "acme");
  CHECK(p.hosts[42].line == 18);
  REQUIRE(p.clusters.size() == 1);
  CHECK(p.clusters[0].id == "acme");
  CHECK(p.clusters[0].size() == 100);
  // A backbone, then two halves per node (SPLITDUPLEX is a cluster's default).
  REQUIRE(p.links.size() == 201);
  CHECK(p.links[0].id == "acme_backbone");
  CHECK(p.links[0].bandwidth == 2.25e9);
  CHECK(p.links[0].latency == 500 / 1e6);
  const SgLink* up = p.find_link("acme_link_7_UP");
  REQUIRE(up != nullptr);
  CHECK(up->bandwidth == 1.25e8);
  CHECK(up->latency == 50 / 1e6);
  CHECK(up->half == DuplexHalf::Up);
  CHECK(up->duplex_id == "acme_link_7");
  CHECK(p.find_link("acme_link_7_DOWN")->half == DuplexHalf::Down);
  CHECK(p.find_link("acme_link_7") == nullptr);
  CHECK(p.routes.empty());
  // The file's own comment: node-0 to node-2 is l0.UP; backbone; l2.DOWN.
  const SgRoute* r = p.find_route("node-0.acme.org", "node-2.acme.org");
  REQUIRE(r != nullptr);
  CHECK(r->src == "node-0.acme.org");
  CHECK(r->dst == "node-2.acme.org");
  CHECK(r->links == Strings{"acme_link_0_UP", "acme_backbone", "acme_link_2_DOWN"});
  CHECK(r->line == 18);
  CHECK(p.find_route("node-2.acme.org", "node-0.acme.org")->links == Strings{"acme_link_2_UP", "acme_backbone", "acme_link_0_DOWN"});
  CHECK(p.find_route("node-0.acme.org", "node-2.acme.org") == r);
  // No loopback given: SimGrid's star routing goes up and down again.
  CHECK(p.find_route("node-5.acme.org", "node-5.acme.org")->links == Strings{"acme_link_5_UP", "acme_backbone", "acme_link_5_DOWN"});
  CHECK(p.find_route("node-5.acme.org", "node-100.acme.org") == nullptr);
  std::size_t pairs = 0;
  std::size_t to_itself = 0;
  p.for_each_route([&](const SgRoute& route) {
    (route.src == route.dst ? to_itself : pairs) += 1;
    CHECK(route.links.size() == 3);
  });
  CHECK(pairs == 100 * 99 / 2);
  CHECK(to_itself == 100);
}

// ---------------------------------------------------------------- what the reader accepts

TEST_CASE("a SPLITDUPLEX link is two halves, and the way back of a symmetrical route swaps them", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(in_zone(kTwoHosts + R"(<link id="x" bandwidth="1GBps" latency="1ms" sharing_policy="SPLITDUPLEX"/>
<link id="y" bandwidth="2GBps"/>
<route src="a" dst="b"><link_ctn id="x" direction="UP"/><link_ctn id="y"/></route>)"),
                                             "duplex.xml");
  REQUIRE(p.links.size() == 3);
  CHECK(p.links[0].id == "x_UP");
  CHECK(p.links[1].id == "x_DOWN");
  CHECK(p.links[1].bandwidth == 1e9);
  CHECK(p.links[1].latency == 1e-3);
  CHECK(p.links[2].latency == 0.0);  // latency defaults to 0
  CHECK(p.routes[0].links == Strings{"x_UP", "y"});
  CHECK(p.find_route("b", "a")->links == Strings{"y", "x_DOWN"});
}

TEST_CASE("a route declared symmetrical=\"NO\" serves one direction only", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(in_zone(kTwoHosts + R"(<link id="l" bandwidth="1GBps"/><link id="m" bandwidth="1GBps"/>
<route src="a" dst="b" symmetrical="NO"><link_ctn id="l"/></route>
<route src="b" dst="a" symmetrical="no"><link_ctn id="m"/></route>)"),
                                             "oneway.xml");
  CHECK_FALSE(p.routes[0].symmetrical);
  CHECK(p.find_route("a", "b")->links == Strings{"l"});
  CHECK(p.find_route("b", "a")->links == Strings{"m"});
  CHECK(p.find_route("b", "a") == &p.routes[1]);
}

TEST_CASE("a host's speed is that of its pstate, its cores default to 1, its properties are kept in order", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(in_zone(R"(<host id="a" speed="100Mf, 50Mf,20Mf" pstate="1" core="4">
  <prop id="ram" value="16GiB"/><prop id="wattage_per_state" value="100.0:200.0"/></host>
<host id="b" speed="1Gf,2Gf"/>)"),
                                             "pstates.xml");
  CHECK(p.hosts[0].speed == 50e6);
  CHECK(p.hosts[0].cores == 4);
  CHECK(p.hosts[0].props == SgProps{{"ram", "16GiB"}, {"wattage_per_state", "100.0:200.0"}});
  CHECK(p.hosts[1].speed == 1e9);
  CHECK(p.hosts[1].cores == 1);
  REQUIRE(p.warnings.size() == 1);
  CHECK_THAT(p.warnings[0], Contains("pstates.xml:4: <prop id=\"wattage_per_state\">: ignored: an energy property cannot change a result"));
  CHECK_THAT(message_of(in_zone(R"(<host id="a" speed="1Gf,2Gf" pstate="2"/>)")),
             Contains("bad.xml:3: <host id=\"a\"> attribute pstate: '2' is not a whole number from 0 to 1"));
  CHECK_THAT(message_of(in_zone(R"(<host id="a" speed="1Gf" core="0"/>)")), Contains("attribute core: '0' is not a whole number from 1"));
  CHECK_THAT(message_of(in_zone(R"(<host id="a" speed="0f"/>)")), Contains("attribute speed: the speed of pstate 0, where the host starts, must be greater than 0"));
  // Another pstate may be 0 (SimGrid's energy_boot.xml switches hosts off so): pcsim runs at the first.
  CHECK(read_simgrid_platform("<platform version=\"4.1\"><zone id=\"z\" routing=\"Full\"><host id=\"a\" speed=\"1Gf, 0f\"/></zone></platform>", "ok.xml")
            .hosts[0]
            .speed == 1e9);
}

TEST_CASE("what cannot change a result is ignored with a warning naming file, line and element", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(R"(<?xml version='1.0'?>
<platform version="4.1">
  <config id="General"><prop id="network/model" value="CM02"/></config>
  <zone id="z" routing="Full">
    <prop id="colour" value="blue"/>
    <host id="a" speed="1000000000" coordinates="1 2 3"/>
    <link id="l" bandwidth="1GBps" latency="3" sharing_policy="FULLDUPLEX"/>
  </zone>
</platform>)",
                                             "warn.xml");
  CHECK(p.hosts[0].speed == 1e9);
  CHECK(p.links[0].latency == 3.0);
  CHECK(p.find_link("l_UP") != nullptr);
  const Strings expected{
      "warn.xml:3: <prop id=\"network/model\">: ignored: SimGrid's configuration tunes SimGrid's models, not pcsim's",
      "warn.xml:5: <prop id=\"colour\">: ignored: a property of a zone cannot change a result",
      "warn.xml:6: <host id=\"a\">: attribute speed: '1000000000' has no unit, read as f (SimGrid does the same, warning that unit-less values are deprecated)",
      "warn.xml:6: <host id=\"a\">: attribute coordinates: ignored (only Vivaldi zones use coordinates)",
      "warn.xml:7: <link id=\"l\">: attribute latency: '3' has no unit, read as s (SimGrid does the same, warning that unit-less values are deprecated)",
      "warn.xml:7: <link id=\"l\">: attribute sharing_policy: FULLDUPLEX is SimGrid's deprecated spelling of SPLITDUPLEX"};
  CHECK(p.warnings == expected);
}

TEST_CASE("nested Full zones are collected, and hosts of different zones have no route", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(R"(<platform version="4">
<AS id="world" routing="Full">
  <link id="shared" bandwidth="1GBps"/>
  <zone id="left" routing="Full"><host id="a" speed="1Gf"/><host id="b" speed="1Gf"/>
    <route src="a" dst="b"><link_ctn id="shared"/></route></zone>
  <AS id="right" routing="Full"><host id="c" speed="1Gf"/></AS>
  <cluster id="c1" prefix="n" suffix="" radical="1,2" speed="1Gf" bw="1GBps" lat="0s" sharing_policy="SHARED"/>
</AS></platform>)",
                                             "nested.xml");
  CHECK(p.hosts.size() == 5);
  CHECK(p.find_route("b", "a")->links == Strings{"shared"});
  CHECK(p.find_route("a", "c") == nullptr);
  CHECK(p.find_route("a", "n1") == nullptr);
  CHECK(p.find_route("n1", "n2")->links == Strings{"c1_link_1", "c1_link_2"});
  CHECK(p.find_route("n2", "n2")->links == Strings{"c1_link_2"});  // SHARED: one link, taken once
}

TEST_CASE("a cluster's limiter and loopback links join its routes as in SimGrid", "[scenario][simgrid]") {
  const SgPlatform p = read_simgrid_platform(R"(<platform version="4.1">
<cluster id="k" prefix="h-" suffix=".org" radical="3,8" speed="2Gf" core="8" bw="10Gbps" lat="10us"
         limiter_link="1GBps" loopback_bw="100GBps" loopback_lat="1us" bb_bw="10GBps" bb_sharing_policy="FATPIPE">
  <prop id="ram" value="64GB"/>
</cluster></platform>)",
                                             "limits.xml");
  REQUIRE(p.hosts.size() == 2);
  CHECK(p.hosts[1].id == "h-8.org");
  CHECK(p.hosts[1].cores == 8);
  CHECK(p.hosts[1].props == SgProps{{"ram", "64GB"}});
  Strings ids;
  for (const SgLink& l : p.links) ids.push_back(l.id);
  CHECK(ids == Strings{"k_backbone", "k_link_3_loopback", "k_link_3_limiter", "k_link_3_UP", "k_link_3_DOWN", "k_link_8_loopback",
                       "k_link_8_limiter", "k_link_8_UP", "k_link_8_DOWN"});
  CHECK(p.find_link("k_backbone")->sharing == LinkSharing::Fatpipe);
  CHECK(p.find_link("k_link_3_loopback")->sharing == LinkSharing::Fatpipe);
  CHECK(p.find_link("k_link_3_loopback")->latency == 1e-6);
  CHECK(p.find_link("k_link_3_limiter")->bandwidth == 1e9);
  CHECK(p.find_link("k_link_3_UP")->bandwidth == 1.25e9);
  CHECK(p.find_route("h-3.org", "h-8.org")->links ==
        Strings{"k_link_3_limiter", "k_link_3_UP", "k_backbone", "k_link_8_DOWN", "k_link_8_limiter"});
  CHECK(p.find_route("h-8.org", "h-8.org")->links == Strings{"k_link_8_loopback"});
}

TEST_CASE("a platform built by hand is searched without its index, and build_index makes the tables", "[scenario][simgrid]") {
  SgPlatform p;
  p.hosts.push_back(SgHost{"a", 1e9, 1, {}, {}, "", 1});
  p.hosts.push_back(SgHost{"b", 1e9, 1, {}, {}, "", 2});
  p.links.push_back(SgLink{"x_UP", 1e9, 0, LinkSharing::Shared, DuplexHalf::Up, "x", {}, 3});
  p.links.push_back(SgLink{"x_DOWN", 1e9, 0, LinkSharing::Shared, DuplexHalf::Down, "x", {}, 3});
  p.routes.push_back(SgRoute{"a", "b", {"x_UP"}, true, 4, "", "", 0});
  for (int pass = 0; pass < 2; ++pass) {
    INFO("pass " << pass);
    CHECK(p.find_host("b") == &p.hosts[1]);
    CHECK(p.find_link("x_DOWN") == &p.links[1]);
    CHECK(p.find_route("a", "b") == &p.routes[0]);
    REQUIRE(p.find_route("b", "a") != nullptr);
    CHECK(p.find_route("b", "a")->links == Strings{"x_DOWN"});
    CHECK(p.find_route("a", "a") == nullptr);
    p.build_index();
  }
  // A copy answers for itself.
  const SgPlatform copy = p;
  CHECK(copy.find_host("a") == &copy.hosts[0]);
  CHECK(copy.find_route("a", "b") == &copy.routes[0]);
}

TEST_CASE("find_route may be called from several threads at once", "[scenario][simgrid]") {
  const SgPlatform p = reference("simgrid/cluster_backbone.xml");
  std::vector<const SgRoute*> seen(4 * 100);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 100; ++i) {
        seen[static_cast<std::size_t>(t * 100 + i)] = p.find_route("node-1.acme.org", "node-" + std::to_string(i) + ".acme.org");
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (int i = 0; i < 100; ++i) {
    for (int t = 1; t < 4; ++t) CHECK(seen[static_cast<std::size_t>(t * 100 + i)] == seen[static_cast<std::size_t>(i)]);
  }
  CHECK(seen[2]->links == Strings{"acme_link_1_UP", "acme_backbone", "acme_link_2_DOWN"});
}

// ---------------------------------------------------------------- refusals

TEST_CASE("malformed XML is refused with the line pugixml stopped at", "[scenario][simgrid]") {
  CHECK(message_of("<platform version=\"4.1\">\n<zone id=\"z\" routing=\"Full\">\n</platform>") == "bad.xml:3: malformed XML: Start-end tags mismatch");
  CHECK_THAT(message_of(""), Contains("bad.xml:1: malformed XML: No document element found"));
  CHECK_THAT(message_of("<platform version=\"4.1\">\n\n<host id=\"a\" speed=1Gf/>"), Contains("bad.xml:3: malformed XML:"));
  CHECK_THAT(message_of("<zone id=\"z\" routing=\"Full\"/>"), Contains("bad.xml:1: <zone id=\"z\">: the document's element should be <platform>"));
  CHECK_THAT(message_of("<platform version=\"4.1\">\n  hello\n</platform>"), Contains("bad.xml:1: <platform>: text is not allowed here"));
}

TEST_CASE("a platform version other than 4 or 4.1 is refused", "[scenario][simgrid]") {
  CHECK(message_of("<platform version=\"3\"/>") == "bad.xml:1: <platform> attribute version: '3' is not supported (versions 4 and 4.1 are)");
  CHECK_THAT(message_of("<platform version=\"4.2\"/>"), Contains("'4.2' is not supported"));
  CHECK_THAT(message_of("<platform/>"), Contains("bad.xml:1: <platform> attribute version: missing"));
  CHECK(read_simgrid_platform("<platform version=\"4.0\"/>", "ok.xml").version == "4");
}

TEST_CASE("an unknown element or attribute is refused, naming it, its line and the closest known name", "[scenario][simgrid]") {
  CHECK(message_of(in_zone("<hots id=\"a\" speed=\"1Gf\"/>")) == "bad.xml:3: <hots id=\"a\">: unknown element inside <zone> (did you mean <host>?)");
  CHECK(message_of(in_zone("\n<host id=\"a\" speed=\"1Gf\" sped=\"2Gf\"/>")) ==
        "bad.xml:4: <host id=\"a\"> attribute sped: unknown attribute (did you mean speed?)");
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\" id=\"b\"/>")), Contains("bad.xml:3: <host id=\"a\"> attribute id: given twice"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\"><link_ctn id=\"l\"/></link>")),
             Contains("bad.xml:3: <link_ctn id=\"l\">: not allowed inside <link>"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><dsik id=\"d\"/></host>")),
             Contains("bad.xml:3: <dsik id=\"d\">: unknown element inside <host> (did you mean <disk>?)"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><prop id=\"p\" value=\"v\"><prop id=\"q\" value=\"w\"/></prop></host>")),
             Contains("bad.xml:3: <prop id=\"q\">: not allowed inside <prop>, which holds nothing"));
}

TEST_CASE("what SimGrid knows and pcsim does not read is refused as not supported", "[scenario][simgrid]") {
  // README, "SimGrid platforms": Vivaldi and Wifi zones and what connects a profile are refused by name.
  CHECK(message_of("<platform version=\"4.1\">\n<zone id=\"z\" routing=\"Vivaldi\"/></platform>") ==
        "bad.xml:2: <zone id=\"z\"> attribute routing: Vivaldi is refused: its latencies come from host coordinates, which pcsim does not model");
  CHECK_THAT(message_of("<platform version=\"4.1\">\n<zone id=\"z\" routing=\"Wifi\"/></platform>"),
             Contains("bad.xml:2: <zone id=\"z\"> attribute routing: Wifi is refused"));
  CHECK_THAT(message_of("<platform version=\"4.1\">\n<zone id=\"z\" routing=\"RuleBased\"/></platform>"),
             Contains("routing 'RuleBased' is not one of Full, Floyd, Dijkstra, DijkstraCache, Cluster, None"));
  CHECK_THAT(message_of(in_zone("<trace_connect kind=\"SPEED\" trace=\"t\" element=\"a\"/>")),
             Contains("bad.xml:3: <trace_connect>: not supported: it connects a profile that changes a host or link over time"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\" availability_file=\"a.txt\"/>")),
             Contains("bad.xml:3: <host id=\"a\"> attribute availability_file: not supported"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\" sharing_policy=\"WIFI\"/>")),
             Contains("<link id=\"l\"> attribute sharing_policy: WIFI is not supported"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\" state_file=\"s\"/>")), Contains("attribute state_file: not supported"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><cluster id=\"c\" prefix=\"\" suffix=\"\" radical=\"0-3\" speed=\"1Gf\" bw=\"1GBps\" "
                        "lat=\"0\" topology=\"RING\"/></platform>"),
             Contains("<cluster id=\"c\"> attribute topology: 'RING' is not one of FLAT, TORUS, FAT_TREE, DRAGONFLY"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><actor host=\"a\" function=\"f\"/></platform>"), Contains("<actor>: not supported"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><zone id=\"a\" routing=\"None\"/><zone id=\"b\" routing=\"Full\"/></platform>"),
             Contains("<zone id=\"b\">: a second top-level zone"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><zone id=\"z\" routing=\"None\">" + kTwoHosts +
                        "<link id=\"l\" bandwidth=\"1Bps\"/><route src=\"a\" dst=\"b\"><link_ctn id=\"l\"/></route></zone></platform>"),
             Contains("<route src=\"a\" dst=\"b\">: a zone with routing=\"None\" has no routes"));
}

TEST_CASE("a route to an unknown host, or one of another zone, is refused", "[scenario][simgrid]") {
  CHECK(message_of(in_zone(kTwoHosts + "<link id=\"l\" bandwidth=\"1GBps\"/>\n<route src=\"a\" dst=\"c\"><link_ctn id=\"l\"/></route>")) ==
        "bad.xml:6: <route src=\"a\" dst=\"c\"> attribute dst: unknown host 'c' (declare hosts before their routes)");
  CHECK_THAT(message_of("<platform version=\"4.1\"><zone id=\"top\" routing=\"Full\"><link id=\"l\" bandwidth=\"1GBps\"/>"
                        "<zone id=\"p\" routing=\"Full\"><host id=\"a\" speed=\"1Gf\"/></zone>"
                        "<zone id=\"q\" routing=\"Full\"><host id=\"b\" speed=\"1Gf\"/>\n"
                        "<route src=\"a\" dst=\"b\"><link_ctn id=\"l\"/></route></zone></zone></platform>"),
             Contains("bad.xml:2: <route src=\"a\" dst=\"b\"> attribute src: host 'a' is in zone 'p', not in this route's zone 'q'"));
}

TEST_CASE("a route with no link, or naming an unknown link or the wrong half, is refused", "[scenario][simgrid]") {
  CHECK(message_of(in_zone(kTwoHosts + "<route src=\"a\" dst=\"b\"/>")) == "bad.xml:5: <route src=\"a\" dst=\"b\">: a route between hosts with no link");
  CHECK(message_of(in_zone(kTwoHosts + "<route src=\"a\" dst=\"b\">\n  <link_ctn id=\"nope\"/></route>")) ==
        "bad.xml:6: <link_ctn id=\"nope\"> attribute id: unknown link 'nope' (declare links before their routes)");
  const std::string duplex = kTwoHosts + "<link id=\"x\" bandwidth=\"1GBps\" sharing_policy=\"SPLITDUPLEX\"/><link id=\"y\" bandwidth=\"1GBps\"/>\n";
  CHECK_THAT(message_of(in_zone(duplex + "<route src=\"a\" dst=\"b\"><link_ctn id=\"x\"/></route>")),
             Contains("bad.xml:6: <link_ctn id=\"x\"> attribute direction: link 'x' is SPLITDUPLEX: say which half, UP or DOWN"));
  CHECK_THAT(message_of(in_zone(duplex + "<route src=\"a\" dst=\"b\"><link_ctn id=\"x_UP\"/></route>")),
             Contains("'x_UP' is a half of SPLITDUPLEX link 'x': write id=\"x\" direction=\"UP\""));
  CHECK_THAT(message_of(in_zone(duplex + "<route src=\"a\" dst=\"b\"><link_ctn id=\"y\" direction=\"UP\"/></route>")),
             Contains("link 'y' is not SPLITDUPLEX"));
  CHECK_THAT(message_of(in_zone(duplex + "<route src=\"a\" dst=\"b\"><link_ctn id=\"x\" direction=\"SIDEWAYS\"/></route>")),
             Contains("attribute direction: 'SIDEWAYS' is not UP, DOWN or NONE"));
}

TEST_CASE("a second route for a direction is refused, the reverse of a symmetrical one included", "[scenario][simgrid]") {
  const std::string links = kTwoHosts + "<link id=\"l\" bandwidth=\"1GBps\"/>\n<route src=\"a\" dst=\"b\"><link_ctn id=\"l\"/></route>\n";
  CHECK(message_of(in_zone(links + "<route src=\"a\" dst=\"b\" symmetrical=\"NO\"><link_ctn id=\"l\"/></route>")) ==
        "bad.xml:7: <route src=\"a\" dst=\"b\">: a second route from 'a' to 'b' (the first at line 6; routes are symmetrical unless "
        "symmetrical=\"NO\")");
  CHECK_THAT(message_of(in_zone(links + "<route src=\"b\" dst=\"a\" symmetrical=\"NO\"><link_ctn id=\"l\"/></route>")),
             Contains("bad.xml:7: <route src=\"b\" dst=\"a\">: a second route from 'b' to 'a' (the first at line 6"));
  CHECK_THAT(message_of(in_zone(kTwoHosts + "<link id=\"l\" bandwidth=\"1GBps\"/>\n<route src=\"a\" dst=\"b\" symmetrical=\"NO\"><link_ctn id=\"l\"/></route>\n"
                                            "<route src=\"b\" dst=\"a\"><link_ctn id=\"l\"/></route>")),
             Contains("bad.xml:7: <route src=\"b\" dst=\"a\">: the route from 'a' to 'b' is declared at line 6: declare this one symmetrical=\"NO\""));
  CHECK_THAT(message_of(in_zone(links + "<route src=\"a\" dst=\"a\" symmetrical=\"maybe\"><link_ctn id=\"l\"/></route>")),
             Contains("attribute symmetrical: 'maybe' is not YES or NO"));
}

TEST_CASE("negative, zero or malformed quantities are refused, naming the attribute", "[scenario][simgrid]") {
  CHECK(message_of(in_zone("<link id=\"l\" bandwidth=\"-5MBps\"/>")) == "bad.xml:3: <link id=\"l\"> attribute bandwidth: '-5MBps' is negative");
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"0MBps\"/>")), Contains("attribute bandwidth: '0MBps': must be greater than 0"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"5MBs\"/>")),
             Contains("bad.xml:3: <link id=\"l\"> attribute bandwidth: '5MBs': unknown bandwidth unit 'MBs'"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\" latency=\"5 min\"/>")), Contains("attribute latency: '5 min': unknown time unit"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"fast\"/>")), Contains("<host id=\"a\"> attribute speed: 'fast' is not a speed"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf,\"/>")), Contains("attribute speed: empty speed"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><disk id=\"d\" read_bw=\"1e999Bps\" write_bw=\"1MBps\"/></host>")),
             Contains("<disk id=\"d\"> attribute read_bw: '1e999Bps' is out of range"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1e308EBps\"/>")), Contains("'1e308EBps' is too large"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\"/>")), Contains("bad.xml:3: <link id=\"l\"> attribute bandwidth: missing"));
  CHECK_THAT(message_of(in_zone("<host id=\"\" speed=\"1Gf\"/>")), Contains("bad.xml:3: <host id=\"\"> attribute id: empty"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><prop id=\"ram\"/></host>")), Contains("<prop id=\"ram\"> attribute value: missing"));
}

TEST_CASE("a host, link, disk, property or zone declared twice is refused", "[scenario][simgrid]") {
  CHECK(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"/>\n<host id=\"a\" speed=\"2Gf\"/>")) ==
        "bad.xml:4: <host id=\"a\"> attribute id: host 'a' is declared twice (first at line 3)");
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\"/>\n<link id=\"l\" bandwidth=\"1GBps\"/>")),
             Contains("bad.xml:4: <link id=\"l\"> attribute id: link 'l' is declared twice (first at line 3)"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\" sharing_policy=\"SPLITDUPLEX\"/>\n<link id=\"l_UP\" bandwidth=\"1GBps\"/>")),
             Contains("bad.xml:4: <link id=\"l_UP\"> attribute id: link 'l_UP' is declared twice (first at line 3)"));
  CHECK_THAT(message_of(in_zone("<link id=\"l\" bandwidth=\"1GBps\" sharing_policy=\"SPLITDUPLEX\"/>\n<link id=\"l\" bandwidth=\"1GBps\"/>")),
             Contains("link 'l' is declared twice"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><disk id=\"d\" read_bw=\"1MBps\" write_bw=\"1MBps\"/>\n"
                                "<disk id=\"d\" read_bw=\"1MBps\" write_bw=\"1MBps\"/></host>")),
             Contains("bad.xml:4: <disk id=\"d\"> attribute id: disk 'd' is declared twice on host 'a'"));
  CHECK_THAT(message_of(in_zone("<host id=\"a\" speed=\"1Gf\"><prop id=\"ram\" value=\"1GB\"/><prop id=\"ram\" value=\"2GB\"/></host>")),
             Contains("<prop id=\"ram\"> attribute id: property 'ram' is given twice"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><zone id=\"z\" routing=\"Full\">\n<zone id=\"z\" routing=\"Full\"/></zone></platform>"),
             Contains("bad.xml:2: <zone id=\"z\"> attribute id: zone 'z' is declared twice (first at line 1)"));
  CHECK_THAT(message_of("<platform version=\"4.1\"><zone id=\"z\" routing=\"Full\"><cluster id=\"c\" prefix=\"n\" suffix=\"\" radical=\"1,1\" "
                        "speed=\"1Gf\" bw=\"1GBps\" lat=\"0\"/></zone></platform>"),
             Contains("<cluster id=\"c\"> attribute radical: host 'n1' is declared twice"));
}

TEST_CASE("a hostile cluster radical fails quickly, naming the attribute", "[scenario][simgrid]") {
  const auto start = std::chrono::steady_clock::now();
  CHECK(message_of("<platform version=\"4.1\">\n<cluster id=\"c\" prefix=\"n\" suffix=\"\" radical=\"0-999999999\" speed=\"1Gf\" bw=\"1GBps\" "
                   "lat=\"0\"/></platform>") ==
        "bad.xml:2: <cluster id=\"c\"> attribute radical: '0-999999999' names more than 100000 hosts, the most a cluster may have here");
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));  // a hang guard, not a timing figure
  // The platform's total is bounded too.
  const std::string two = "<platform version=\"4.1\"><zone id=\"z\" routing=\"Full\">"
                          "<cluster id=\"c\" prefix=\"a\" suffix=\"\" radical=\"0-5\" speed=\"1Gf\" bw=\"1GBps\" lat=\"0\"/>"
                          "<cluster id=\"d\" prefix=\"b\" suffix=\"\" radical=\"0-5\" speed=\"1Gf\" bw=\"1GBps\" lat=\"0\"/></zone></platform>";
  CHECK(read_simgrid_platform(two, "ok.xml", SgLimits{6, 12}).hosts.size() == 12);
  CHECK_THROWS_WITH(read_simgrid_platform(two, "bad.xml", SgLimits{6, 11}),
                    Contains("<cluster id=\"d\"> attribute radical: '0-5' names more than 5 hosts"));
  CHECK_THAT(message_of(std::string(200, ' ') + "<platform version=\"4.1\">" + std::string(100, '\n') +
                        "<cluster id=\"c\" prefix=\"n\" suffix=\"\" radical=\"0-x\" speed=\"1Gf\" bw=\"1GBps\" lat=\"0\"/></platform>"),
             Contains("bad.xml:101: <cluster id=\"c\"> attribute radical: '0-x': 'x' is not a number"));
}

TEST_CASE("zones nested beyond a bound are refused rather than overflowing the stack", "[scenario][simgrid]") {
  std::string text = "<platform version=\"4.1\">";
  for (int i = 0; i < 100'000; ++i) text += "<zone id=\"z" + std::to_string(i) + "\" routing=\"Full\">";
  for (int i = 0; i < 100'000; ++i) text += "</zone>";
  text += "</platform>";
  CHECK_THAT(message_of(text), Contains("<zone id=\"z64\">: zones nested more than 64 deep"));
}

// ---------------------------------------------------------------- the fuzz target's contract

