// pcsim calibrate without measuring: its readers of /proc and /sys on texts as the kernel
// writes them, and its platform file read back by pcsim's own loader.
#include "calibrate/calibrate.hpp"
#include "calibrate/measure.hpp"
#include "calibrate/system_info.hpp"

#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>

using namespace pagecache;
using namespace pagecache::calibrate;

TEST_CASE("calibrate reads /proc/meminfo, a sysfs choice and /proc/cpuinfo as the kernel writes them", "[calibrate]") {
  const std::string meminfo = "MemTotal:       24684432 kB\nMemFree:        20110200 kB\nMemAvailable:   23031136 kB\nHugePages_Total:       0\n";
  CHECK(meminfo_bytes(meminfo, "MemTotal") == 24684432LL * 1024);
  CHECK(meminfo_bytes(meminfo, "MemAvailable") == 23031136LL * 1024);
  CHECK(meminfo_bytes(meminfo, "HugePages_Total") == 0);
  CHECK(meminfo_bytes(meminfo, "Mem") == -1);  // a prefix is not a field
  CHECK(meminfo_bytes(meminfo, "Dirty") == -1);
  CHECK(selected_choice("always [madvise] never\n") == "madvise");
  CHECK(selected_choice("[always] madvise never") == "always");
  const std::string cpuinfo = "processor\t: 0\nvendor_id\t: GenuineIntel\nmodel name\t: Intel(R) Xeon(R) Gold 6130 CPU @ 2.10GHz\n"
                              "flags\t\t: fpu vme sse2 hypervisor avx512f\n\nprocessor\t: 1\n";
  CHECK(cpuinfo_model(cpuinfo) == "Intel(R) Xeon(R) Gold 6130 CPU @ 2.10GHz");
  CHECK(cpuinfo_hypervisor(cpuinfo));
  CHECK_FALSE(cpuinfo_hypervisor("model name\t: X\nflags\t\t: fpu vme sse2\n"));
  CHECK(cpuinfo_model("processor\t: 0\n").empty());
}

TEST_CASE("calibrate reads the CPUs' time from /proc/stat and a virtio balloon's free page reporting from sysfs", "[calibrate]") {
  // user nice system idle iowait irq softirq steal guest guest_nice, in ticks of 100 per second
  const CpuTimes t = proc_stat_cpu("cpu  1000 50 300 9000 200 10 40 400 0 0\ncpu0 500 25 150 4500 100 5 20 200 0 0\n", 100.0);
  CHECK(t.busy == Approx(14.0));  // 1000 + 50 + 300 + 10 + 40
  CHECK(t.steal == Approx(4.0));
  CHECK(t.total == Approx(110.0));
  CHECK(proc_stat_cpu("intr 1 2 3\n", 100.0).total == 0.0);
  // sysfs `features`: one character per feature bit, bit 0 first; bit 5 is VIRTIO_BALLOON_F_REPORTING.
  const std::string reporting = "0110010100000000000000000000000010000000\n";
  CHECK(virtio_balloon("0x0005\n"));
  CHECK_FALSE(virtio_balloon("0x0002\n"));  // a block device
  CHECK(virtio_balloon_reporting("0x0005\n", reporting));
  CHECK_FALSE(virtio_balloon_reporting("0x0005\n", "0110000100000000\n"));
  CHECK_FALSE(virtio_balloon_reporting("0x0002\n", reporting));  // the same bit on another device means something else
  // Activity over a moment: this process's own CPU time is not counted as others'.
  const ActivityMark mark;
  volatile double x = 1.0;
  for (int i = 0; i < 20'000'000; ++i) x = x * 1.0000001;
  const Activity a = mark.since();
  CHECK(a.seconds > 0.0);
  CHECK(a.others_busy_cores >= 0.0);
  CHECK(a.steal_pct >= 0.0);
}

TEST_CASE("the calibrated platform file is one pcsim loads, each value as measured, an unmeasured one left out", "[calibrate]") {
  Calibration c;
  c.date = "2026-12-03T12:00:00Z";
  c.system.hostname = "node-7";
  c.system.cpu_model = "Test CPU";
  c.system.cores = 8;
  c.system.memory_total = 16LL << 30;
  c.system.memory_available = 15LL << 30;
  c.system.dirty_ratio = 0.3;
  c.system.dirty_background_ratio = 0.05;
  c.system.dirty_expire = 20.0;
  c.system.writeback_interval = 2.5;
  c.size = 1LL << 30;
  c.streams = 4;
  const auto measured = [](double v) { return Figure{v, "a method", true}; };
  c.disk_read = measured(500e6);
  c.writeback = measured(400e6);
  c.disk_write = Figure{300e6, "O_DIRECT", true};  // for comparison only
  c.disk_aggregate_read = measured(900e6);
  c.aggregate_writeback = measured(450e6);
  c.memory_read = measured(6000e6);
  c.memory_write = measured(3000e6);
  c.memory_aggregate_read = measured(20000e6);
  c.memory_aggregate_write = measured(9000e6);
  c.first_touch = measured(2000e6);
  c.memory_reclaimed_write = Figure{0.0, "not measured with --quick", false};
  c.notes.push_back("a note");
  const std::string toml = platform_toml(c);
  INFO(toml);
  CHECK_THAT(toml, Catch::Contains("# Note: a note") && Catch::Contains("# memory_reclaimed_write_bw not set: not measured with --quick") &&
                       Catch::Contains("# a method\nread_bw = \"500 MB/s\"") &&
                       Catch::Contains("# for comparison: O_DIRECT: 300 MB/s"));
  const Scenario s = parse_scenario(toml + "\n[pipelines]\nfile_size = \"1 GB\"\n", "<calibrated>");
  REQUIRE(s.hosts.size() == 1);
  const HostConfig& h = s.hosts[0];
  CHECK(h.name == "node-7");
  CHECK(h.cores == 8);
  CHECK(h.memory == 16LL << 30);
  CHECK(h.memory_in_use == 1LL << 30);
  CHECK(h.memory_bandwidth.read == 6000e6);
  CHECK(h.memory_bandwidth.write == 3000e6);
  CHECK(h.memory_bandwidth.aggregate_read == 20000e6);
  CHECK(h.memory_bandwidth.aggregate_write == 9000e6);
  CHECK(h.memory_bandwidth.first_touch == 2000e6);
  CHECK(h.memory_bandwidth.reclaimed_write == 0.0);  // as into free pages
  CHECK(h.cache.dirty_ratio == Approx(0.3));
  CHECK(h.cache.dirty_background_ratio == Approx(0.05));
  CHECK(h.cache.dirty_expire == 20.0);
  CHECK(h.cache.writeback_interval == 2.5);
  REQUIRE(h.disks.size() == 1);
  CHECK(h.disks[0].read_bw == 500e6);
  CHECK(h.disks[0].write_bw == 400e6);
  CHECK(h.disks[0].aggregate_read_bw == 900e6);
  CHECK(h.disks[0].aggregate_write_bw == 450e6);

  // dirty_bytes in place of the ratios: as fractions of the memory.
  c.system.dirty_bytes = 4LL << 30;
  c.system.dirty_background_bytes = 1LL << 30;
  const Scenario b = parse_scenario(platform_toml(c) + "\n[pipelines]\nfile_size = \"1 GB\"\n", "<calibrated>");
  CHECK(b.hosts[0].cache.dirty_ratio == Approx(0.25));
  CHECK(b.hosts[0].cache.dirty_background_ratio == Approx(0.0625));
}

TEST_CASE("a measurement whose deadline passed before it began still times one request", "[calibrate]") {
  // On a loaded machine (a sanitized build beside other jobs) the deadline of a short
  // measurement could pass before its first request: it measured nothing, and the platform
  // file lacked a required key. One request is always made; only an interrupt stops it first.
  const std::filesystem::path file = std::filesystem::temp_directory_path() / ("pcsim-deadline-" + std::to_string(::getpid()));
  const Deadline passed(-1.0);
  const Rate written = cache_write(file, 1 << 20, 1 << 16, passed);
  CHECK(written.bytes == 1 << 16);
  CHECK(written.seconds > 0.0);
  const Rate read = cached_read(file, 1 << 16, false, passed);
  CHECK(read.bytes == 1 << 16);
  CHECK(read.seconds > 0.0);
  std::filesystem::remove(file);
}
