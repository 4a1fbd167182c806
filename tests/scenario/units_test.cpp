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
