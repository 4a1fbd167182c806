// Uses only the installed public API: four 100 MB reads share a 100 MB/s disk.
#include <pagecache/devices.hpp>
#include <pagecache/simulator.hpp>

#include <cstdio>

namespace {
pagecache::Task<void> reader(const pagecache::Disk& disk) { co_await disk.read(100'000'000); }
}  // namespace

int main() {
  pagecache::Simulator sim;
  pagecache::FairShare share(sim);
  pagecache::Disk disk(share, "disk", 100e6, 100e6);
  for (int i = 0; i < 4; ++i) sim.spawn(reader(disk));
  sim.run();
  std::printf("done at %g s\n", sim.now());
  return sim.now() == 4.0 ? 0 : 1;
}
