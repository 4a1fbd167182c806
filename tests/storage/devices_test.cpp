#include <pagecache/devices.hpp>
#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

using namespace pagecache;

TEST_CASE("devices report what they were built with", "[devices]") {
  Simulator sim;
  FairShare share(sim);
  Disk disk(share, "sda", 510e6, 420e6, 450'000'000'000);
  CHECK(disk.name() == "sda");
  CHECK(disk.read_bandwidth() == 510e6);
  CHECK(disk.write_bandwidth() == 420e6);
  CHECK(disk.capacity() == 450'000'000'000);
  CHECK(disk.read_usage().cost == Catch::Detail::Approx(1.0 / 510e6));
  Cpu cpu(share, "cpu", 32);
  CHECK(cpu.cores() == 32);
  CHECK(share.resource_count() == 2);
  CHECK_THROWS_AS(Link(share, "nfs", 3e9, -1.0), ConfigError);
  CHECK_THROWS_AS(Memory(share, "mem", MemoryBandwidth{1, 1, 0, 1}), ConfigError);
  CHECK_THROWS_AS(disk.read(-5), SimulationError);
}
