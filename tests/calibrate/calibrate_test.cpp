// pcsim calibrate without measuring: its readers of /proc and /sys on texts as the kernel
// writes them, its fits and findings on made-up measurements, and its platform file read back
// by pcsim's own loader.
#include "calibrate/calibrate.hpp"
#include "calibrate/measure.hpp"
#include "calibrate/system_info.hpp"

#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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

  // The multi-generation LRU's main switch on: the platform says mglru; off or absent: the
  // profile's policy stays.
  CHECK(b.hosts[0].cache.policy == CacheSettings::kernel().policy);
  CHECK_THAT(platform_toml(c), Catch::Contains("lru_gen/enabled absent") && !Catch::Contains("policy ="));
  for (const char* on : {"0x0007", "0x0001", "0x0003"}) {
    c.system.lru_gen = on;
    CHECK(parse_scenario(platform_toml(c) + "\n[pipelines]\nfile_size = \"1 GB\"\n", "<calibrated>").hosts[0].cache.policy == "mglru");
  }
  for (const char* off : {"0x0000", "0x0006", ""}) {
    c.system.lru_gen = off;
    CHECK(parse_scenario(platform_toml(c) + "\n[pipelines]\nfile_size = \"1 GB\"\n", "<calibrated>").hosts[0].cache.policy != "mglru");
  }
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

namespace {

RequestRate at_rate(std::int64_t size, double rate) { return RequestRate{size, Figure{rate, "", true, 0.0, rate, rate}}; }

std::vector<Rate> pieces_at(const std::vector<double>& rates_mb) {
  std::vector<Rate> pieces;
  for (const double r : rates_mb) pieces.push_back(Rate{256LL << 20, static_cast<double>(256LL << 20) / (r * 1e6)});
  return pieces;
}

}  // namespace

TEST_CASE("the request latency is the intercept of time per request against size, held at 0 when the fit goes below", "[calibrate]") {
  // Exact: t = 0.05 ms + s / 1.5 GB/s at every size; the weighted fit gives both back.
  std::vector<RequestRate> rates;
  for (const std::int64_t size : {64LL << 10, 256LL << 10, 1LL << 20, 4LL << 20, 16LL << 20}) {
    const double s = static_cast<double>(size);
    rates.push_back(at_rate(size, s / (50e-6 + s / 1.5e9)));
  }
  const RequestFit exact = fit_request_latency(rates);
  REQUIRE(exact.fitted);
  CHECK_FALSE(exact.clamped);
  CHECK(exact.latency == Approx(50e-6));
  CHECK(exact.bandwidth == Approx(1.5e9));
  // Small requests faster than large ones: through (64 KiB, 2 GB/s) and (16 MiB, 1 GB/s) the
  // line meets size 0 below 0. Held at 0, the slope through the origin with weights 1/t^2 is
  // 1/B = sum(s/t) / sum(s^2/t^2), so B = sum(rate^2) / sum(rate) = (4 + 1) / 3 GB/s.
  const RequestFit clamped = fit_request_latency({at_rate(64LL << 10, 2e9), at_rate(16LL << 20, 1e9)});
  REQUIRE(clamped.fitted);
  CHECK(clamped.clamped);
  CHECK(clamped.latency == 0.0);
  CHECK(clamped.bandwidth == Approx(5e9 / 3.0));
  // One size is no line; an unmeasured size does not count.
  CHECK_FALSE(fit_request_latency({at_rate(16LL << 20, 1e9)}).fitted);
  CHECK_FALSE(fit_request_latency({at_rate(16LL << 20, 1e9), RequestRate{1LL << 20, Figure{}}}).fitted);
  const std::string toml = request_latency_toml(rates, exact, 1LL << 30);
  INFO(toml);
  CHECK_THAT(toml, Catch::Contains("#     64 KiB") && Catch::Contains("#     16 MiB") && Catch::Contains("request_latency = \"0.050 ms\"\n"));
}

TEST_CASE("a write cache is where the pieces' rate falls for good, not where it dips", "[calibrate]") {
  // 16 pieces of 256 MiB at about 2 GB/s, then 500 MB/s: the cache held 4 GiB.
  std::vector<double> fall;
  for (int i = 0; i < 16; ++i) fall.push_back(i % 2 == 0 ? 1900.0 : 2100.0);
  for (int i = 0; i < 8; ++i) fall.push_back(i % 2 == 0 ? 490.0 : 510.0);
  const WriteCacheFinding f = find_write_cache(pieces_at(fall));
  CHECK(f.fell);
  CHECK(f.fall == 16);
  CHECK(f.cache_bytes == 4LL << 30);
  CHECK(f.burst == Approx(2100e6));  // the median of 8 x 1900 and 8 x 2100: the upper middle
  CHECK(f.sustained == Approx(510e6));
  CHECK(write_rate_settled(pieces_at(fall)));
  // Two pieces after the fall are not yet a fall, and so not settled.
  const std::vector<double> early(fall.begin(), fall.begin() + 18);
  CHECK_FALSE(find_write_cache(pieces_at(early)).fell);
  CHECK_FALSE(write_rate_settled(pieces_at(early)));
  // After a fall, pieces 30 % apart are not settled.
  std::vector<double> unsettled(fall.begin(), fall.begin() + 16);
  for (int i = 0; i < 8; ++i) unsettled.push_back(i % 2 == 0 ? 400.0 : 560.0);
  CHECK(find_write_cache(pieces_at(unsettled)).fell);
  CHECK_FALSE(write_rate_settled(pieces_at(unsettled)));

  // Flat and noisy (1.8 to 3.3 GB/s, as this VM's host), with single dips and a dip of three
  // pieces, and a dip of four that recovers: no cache.
  std::vector<double> flat;
  for (int i = 0; i < 48; ++i) flat.push_back(std::vector<double>{1800.0, 3300.0, 2500.0, 2900.0}[i % 4]);
  flat[10] = 300.0;
  flat[20] = flat[21] = flat[22] = 900.0;
  flat[30] = flat[31] = flat[32] = flat[33] = 900.0;
  const WriteCacheFinding none = find_write_cache(pieces_at(flat));
  CHECK_FALSE(none.fell);
  CHECK(none.cache_bytes == 0);
  CHECK(none.sustained == Approx(2500e6));
  CHECK_FALSE(write_rate_settled(pieces_at(flat)));
  // A cache smaller than two pieces: the first fast, every later one slow.
  const WriteCacheFinding small = find_write_cache(pieces_at({3000.0, 1000.0, 1050.0, 980.0, 1010.0, 1000.0}));
  CHECK(small.fell);
  CHECK(small.cache_bytes == 256LL << 20);

  // In the platform: both keys from a fall, none from a flat run, nor from a sustained rate
  // above writeback's. pcsim's medium drains the cache as it fills, so the cache that took 4 GiB
  // at 2100 MB/s with 510 MB/s drained meanwhile holds 4 GiB x (1 - 510/2100) = 3101.3 MiB.
  WriteCache w;
  w.measured = true;
  w.pieces = pieces_at(fall);
  w.finding = find_write_cache(w.pieces);
  w.stopped = "settled after the fall";
  std::string toml = write_cache_toml(w, 3000e6);
  INFO(toml);
  CHECK_THAT(toml, Catch::Contains("write_cache = \"3101 MiB\"\n") && Catch::Contains("sustained_write_bw = \"510 MB/s\"\n") &&
                       Catch::Contains("#   1900 2100 1900"));
  CHECK_THAT(write_cache_toml(w, 400e6), Catch::Contains("# write_cache, sustained_write_bw not set: the rate fell") &&
                                             !Catch::Contains("write_cache = "));
  w.pieces = pieces_at(flat);
  w.finding = find_write_cache(w.pieces);
  CHECK_THAT(write_cache_toml(w, 3000e6), Catch::Contains("# write_cache, sustained_write_bw not set: no write cache found: 12.0 GiB at 2500 MB/s"));
  w.setting.quick = true;
  w.pieces = pieces_at(fall);
  w.finding = find_write_cache(w.pieces);
  CHECK_THAT(write_cache_toml(w, 3000e6), Catch::Contains("not set: --quick") && !Catch::Contains("write_cache = "));
}

TEST_CASE("the cold fault rate is what memory the host took back adds per byte, given only when it stands out of the noise", "[calibrate]") {
  // 1 / (1/502 - 1/2878 MB/s) = 502 * 2878 / (2878 - 502) MB/s = 608.1 MB/s.
  const Figure warm{2878e6, "", true, 5.0, 2800e6, 2950e6};
  const Figure cold{502e6, "", true, 8.0, 480e6, 520e6};
  const ColdFault f = cold_fault_rate(true, warm, cold);
  REQUIRE(f.known);
  CHECK(f.rate == Approx(502e6 * 2878e6 / (2878e6 - 502e6)));
  CHECK_THAT(cold_fault_toml(f, warm, cold), Catch::Contains("memory_cold_fault_bw = \"608 MB/s\"\n") &&
                                                 Catch::Contains("page_reporting_delay = \"2 s\"\n"));
  // Apart by less than their spreads: the slowest just-freed write below the fastest cold one,
  // or (this VM, a reporting cycle catching some just-freed memory) the ranges apart but the
  // medians 354 MB/s apart where the ranges are 2323 and 6 MB/s wide.
  const Figure noisy_warm{2878e6, "", true, 90.0, 500e6, 3100e6};
  CHECK_FALSE(cold_fault_rate(true, noisy_warm, cold).known);
  CHECK_FALSE(cold_fault_rate(true, Figure{758e6, "", true, 307.0, 661e6, 2984e6}, Figure{404e6, "", true, 2.0, 403e6, 409e6}).known);
  CHECK_THAT(cold_fault_toml(cold_fault_rate(true, noisy_warm, cold), noisy_warm, cold),
             Catch::Contains("# memory_cold_fault_bw, page_reporting_delay not set: ") && !Catch::Contains("memory_cold_fault_bw = "));
  CHECK_FALSE(cold_fault_rate(false, warm, cold).known);  // no free page reporting
  CHECK_FALSE(cold_fault_rate(true, warm, Figure{}).known);
}

TEST_CASE("calibrate reads the readahead and the largest request of the device under a folder from sysfs", "[calibrate]") {
  // A sysfs tree as the kernel lays it out: a disk, its partition, an NFS mount's bdi.
  namespace fs = std::filesystem;
  const fs::path sys = fs::temp_directory_path() / ("pcsim-sysfs-" + std::to_string(::getpid()));
  const auto write = [](const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
  };
  const fs::path vda = sys / "devices/pci0000:00/virtio2/block/vda";
  write(vda / "dev", "254:0\n");
  write(vda / "queue/read_ahead_kb", "8192\n");
  write(vda / "queue/max_sectors_kb", "4096\n");
  write(vda / "vda1/dev", "254:1\n");
  write(vda / "vda1/partition", "1\n");
  write(sys / "class/bdi/254:0/read_ahead_kb", "128\n");  // unlike the queue's, to tell which was read
  write(sys / "class/bdi/0:53/read_ahead_kb", "15360\n");
  fs::create_directories(sys / "dev/block");
  fs::create_directory_symlink("../../devices/pci0000:00/virtio2/block/vda", sys / "dev/block/254:0");
  fs::create_directory_symlink("../../devices/pci0000:00/virtio2/block/vda/vda1", sys / "dev/block/254:1");

  const DeviceLimits disk = read_device_limits(sys, 254, 0);
  CHECK(disk.device == "vda");
  CHECK(disk.read_ahead == 128 * 1024);  // the bdi's first
  CHECK(disk.max_request == 4096 * 1024);
  const DeviceLimits partition = read_device_limits(sys, 254, 1);
  CHECK(partition.device == "vda");
  CHECK(partition.read_ahead == 128 * 1024);  // the disk's bdi
  CHECK(partition.max_request == 4096 * 1024);  // the disk's queue
  fs::remove(sys / "class/bdi/254:0/read_ahead_kb");
  CHECK(read_device_limits(sys, 254, 1).read_ahead == 8192 * 1024);  // no bdi: the queue's
  const DeviceLimits nfs = read_device_limits(sys, 0, 53);
  CHECK(nfs.device.empty());
  CHECK(nfs.read_ahead == 15360 * 1024);
  CHECK(nfs.max_request == -1);
  CHECK_THAT(nfs.max_request_from, Catch::Contains("not a block device"));
  const DeviceLimits unknown = read_device_limits(sys, 0, 99);
  CHECK(unknown.read_ahead == -1);
  CHECK(unknown.max_request == -1);
  fs::remove_all(sys);
}

TEST_CASE("the calibrated platform file gives the device's requests, its write cache and cold memory where they were found", "[calibrate]") {
  Calibration c;
  c.date = "2026-12-03T12:00:00Z";
  c.system.hostname = "node-7";
  c.system.memory_total = 16LL << 30;
  c.system.memory_available = 15LL << 30;
  c.system.free_page_reporting = true;
  c.system.device = DeviceLimits{"vda", 8192 * 1024, 4096 * 1024, "/sys/class/bdi/254:0/read_ahead_kb", "/sys/dev/block/254:0/queue/max_sectors_kb"};
  c.size = 1LL << 30;
  c.streams = 4;
  const auto measured = [](double v) { return Figure{v, "a method", true, 0.0, v, v}; };
  c.disk_read = measured(1500e6);
  c.writeback = measured(3000e6);
  c.memory_read = measured(6000e6);
  c.memory_write = measured(2878e6);
  c.memory_write_cold = measured(502e6);
  c.cold_fault = cold_fault_rate(true, c.memory_write, c.memory_write_cold);
  c.request_rates = {at_rate(1LL << 20, 1e9), at_rate(16LL << 20, 1.5e9)};
  c.request_fit = fit_request_latency(c.request_rates);
  c.write_cache.measured = true;
  c.write_cache.pieces = pieces_at({2000, 2000, 2000, 2000, 500, 500, 500, 500});
  c.write_cache.finding = find_write_cache(c.write_cache.pieces);
  const std::string toml = platform_toml(c);
  INFO(toml);
  CHECK_THAT(toml, Catch::Contains("\nrequest_latency = \"") && Catch::Contains("\nread_ahead = \"8192 KiB\"\n") &&
                       Catch::Contains("\nmax_request = \"4096 KiB\"\n") && Catch::Contains("\nwrite_cache = \"768 MiB\"\n") &&
                       Catch::Contains("\nsustained_write_bw = \"500 MB/s\"\n") && Catch::Contains("\nmemory_cold_fault_bw = \"608 MB/s\"\n") &&
                       Catch::Contains("\npage_reporting_delay = \"2 s\"\n") &&
                       Catch::Contains("read, not measured: /sys/class/bdi/254:0/read_ahead_kb (vda)"));
  // The host's keys before its page cache table, the disk's after its name; pcsim reads them.
  CHECK(toml.find("memory_cold_fault_bw") < toml.find("[hosts.page_cache]"));
  CHECK(toml.find("write_cache = ") > toml.find("[[hosts.disks]]"));
  const Scenario s = parse_scenario(toml + "\n[pipelines]\nfile_size = \"1 GB\"\n", "<calibrated>");
  REQUIRE(s.hosts.size() == 1);
  REQUIRE(s.hosts[0].disks.size() == 1);
  const DiskSpec& d = s.hosts[0].disks[0];
  CHECK(d.request_latency == Approx(c.request_fit.latency).margin(1e-6));  // written in ms to 3 decimals
  CHECK(d.read_ahead == 8192 * 1024);
  CHECK(d.max_request == 4096 * 1024);
  CHECK(d.write_cache == 768LL << 20);
  CHECK(d.sustained_write_bw == 500e6);
  CHECK(s.hosts[0].memory_bandwidth.cold_fault == 608e6);
  CHECK(s.hosts[0].page_reporting_delay == 2.0);
}
