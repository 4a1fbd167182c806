// The SimGrid platform reader: SimGrid's units and cluster radicals.

#include "scenario/simgrid_radical.hpp"
#include "scenario/simgrid_units.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

using namespace pagecache;
using namespace pagecache::scenario;
using Catch::Contains;

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
  CHECK(parse_sg_time("50us") == 50 * 1e-6);
  CHECK(parse_sg_time("1.461517ms") == 1.461517 * 1e-3);
  CHECK(parse_sg_time("3ns") == 3 * 1e-9);
  CHECK(parse_sg_time("4ps") == 4 * 1e-12);
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
