#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <catch2/catch.hpp>

using namespace pagecache;

TEST_CASE("sizes read decimal and binary units and never confuse them", "[units]") {
  CHECK(units::parse_size("3 GB") == 3'000'000'000);
  CHECK(units::parse_size("3GB") == 3'000'000'000);
  CHECK(units::parse_size("3 GiB") == 3LL << 30);
  CHECK(units::parse_size("1.5 MB") == 1'500'000);
  CHECK(units::parse_size("512 KiB") == 512 * 1024);
  CHECK(units::parse_size("42") == 42);
  CHECK(units::parse_size(" 7 B ") == 7);
  CHECK_THROWS_AS(units::parse_size("-1 GB"), ConfigError);
  CHECK_THROWS_WITH(units::parse_size("3 gigs"), Catch::Contains("unknown size unit 'gigs'"));
  CHECK_THROWS_AS(units::parse_size("GB"), ConfigError);
}

TEST_CASE("bandwidths are sizes per second", "[units]") {
  CHECK(units::parse_bandwidth("465 MB/s") == 465e6);
  CHECK(units::parse_bandwidth("1 GiB/s") == static_cast<double>(1LL << 30));
  CHECK(units::parse_bandwidth("100") == 100.0);
  CHECK_THROWS_WITH(units::parse_bandwidth("465 MB"), Catch::Contains("size per second"));
}

TEST_CASE("durations read ns to hours", "[units]") {
  CHECK(units::parse_duration("30 s") == 30.0);
  CHECK(units::parse_duration("250 ms") == Catch::Detail::Approx(0.25));
  CHECK(units::parse_duration("20 us") == Catch::Detail::Approx(2e-5));
  CHECK(units::parse_duration("2 min") == 120.0);
  CHECK(units::parse_duration("1.5 h") == 5400.0);
  CHECK(units::parse_duration("4.4") == 4.4);
  CHECK_THROWS_AS(units::parse_duration("-3 s"), ConfigError);
}

TEST_CASE("formatted sizes read back exactly", "[units]") {
  for (std::int64_t bytes : {0LL, 1LL, 999LL, 1000LL, 3'000'000'000LL, 3LL << 30, 98'304'352LL, 450LL << 30}) {
    CHECK(units::parse_size(units::format_size(bytes)) == bytes);
  }
  CHECK(units::format_size(3'000'000'000) == "3 GB");
  CHECK(units::format_size(3LL << 30) == "3 GiB");
  CHECK(units::parse_bandwidth(units::format_bandwidth(465e6)) == 465e6);
}

TEST_CASE("sizes run up to exabytes and no further than 1 EiB", "[units]") {
  CHECK(units::parse_size("2 PB") == 2'000'000'000'000'000);
  CHECK(units::parse_size("1 EB") == 1'000'000'000'000'000'000);
  CHECK(units::parse_size("1 PiB") == 1LL << 50);
  CHECK(units::parse_size("1 EiB") == units::kMaxBytes);
  CHECK(units::parse_size("3.7") == 4);  // whole bytes, rounded
  CHECK_THROWS_WITH(units::parse_size("2 EB"), Catch::Contains("too large"));
  CHECK_THROWS_WITH(units::parse_size("1e300 TB"), Catch::Contains("too large"));
}

TEST_CASE("network bandwidths read in bits per second", "[units]") {
  CHECK(units::parse_bandwidth("10 Gbit/s") == 1.25e9);
  CHECK(units::parse_bandwidth("100 Mbit/s") == 12.5e6);
  CHECK(units::parse_bandwidth("8 kbit/s") == 1e3);
  CHECK_THROWS_WITH(units::parse_bandwidth("1e300 TB/s"), Catch::Contains("too large"));
  CHECK_THROWS_WITH(units::parse_duration("1e307 h"), Catch::Contains("too large"));
}

TEST_CASE("a unit in the wrong case or a common misspelling is named with the right one", "[units]") {
  CHECK_THROWS_WITH(units::parse_size("8 gb"), Catch::Contains("unknown size unit 'gb' (did you mean 'GB'?)"));
  CHECK_THROWS_WITH(units::parse_size("8 gib"), Catch::Contains("(did you mean 'GiB'?)"));
  CHECK_THROWS_WITH(units::parse_size("8 kb"), Catch::Contains("(did you mean 'kB'?)"));
  CHECK_THROWS_WITH(units::parse_bandwidth("1 Gbps"), Catch::Contains("(did you mean 'Gbit/s'?)"));
  CHECK_THROWS_WITH(units::parse_bandwidth("1 gbit/s"), Catch::Contains("(did you mean 'Gbit/s'?)"));
  CHECK_THROWS_WITH(units::parse_bandwidth("1 mib/s"), Catch::Contains("(did you mean 'MiB/s'?)"));
  // A lower-case b is a bit: both readings are offered.
  CHECK_THROWS_WITH(units::parse_bandwidth("1 Mb/s"), Catch::Contains("(did you mean 'MB/s' or 'Mbit/s'?)"));
  CHECK_THROWS_WITH(units::parse_bandwidth("465 MB"), Catch::Contains("a bandwidth is a size per second (did you mean 'MB/s'?)"));
  CHECK_THROWS_WITH(units::parse_duration("3 m"), Catch::Contains("(did you mean 'min'?)"));
  CHECK_THROWS_WITH(units::parse_duration("3 seconds"), Catch::Contains("(did you mean 's'?)"));
  CHECK_THROWS_WITH(units::parse_duration("3 parsecs"), Catch::Contains("(use ns, us, ms, s, min, h)"));
}

TEST_CASE("a moment of simulated time in a message has six decimals, or a short exponent when it went astray", "[units]") {
  using pagecache::units::format_instant;
  CHECK(format_instant(12.5) == "12.500000");
  CHECK(format_instant(1e9) == "1000000000.000000");
  CHECK(format_instant(1.1675832127351664e300) == "1.16758e+300");
  CHECK(format_instant(2e10) == "2e+10");
}
