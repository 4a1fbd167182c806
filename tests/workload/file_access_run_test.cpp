// Accesses of parts of one file, run: reads hit exactly what is cached (a cached file, a range
// read before, a range written before), random reads under POSIX_FADV_RANDOM read only what
// they ask for, an append's data is in the cache for the read after it, and a strided
// hyperslab that fits the cache is read from it in epoch 2.

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pagecache {
namespace {

constexpr double kMemoryBw = 10e9;
constexpr double kDiskBw = 500e6;
constexpr double kLatency = 100e-6;
constexpr std::int64_t kMiB = 1 << 20;

// A 1 GB host whose disk takes kLatency per request (and `disk_keys`); file "hot" (8 MiB,
// cached at the start) and "cold" (8 MiB) and "big" (64 MiB), then one task whose accesses are
// `accesses` (TOML of [[apps.tasks.access]] tables).
Scenario with_accesses(const std::string& profile, const std::string& accesses, const std::string& disk_keys = "") {
  return parse_scenario(fmt::format(R"(profile = "{}"
[[hosts]]
name = "node"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
request_latency = "100 us"
{}
[[files]]
name = "hot"
size = "8 MiB"
cached = true
[[files]]
name = "cold"
size = "8 MiB"
[[files]]
name = "big"
size = "64 MiB"
[[apps]]
name = "app"
[[apps.tasks]]
name = "t"
{}
)",
                                    profile, disk_keys, accesses),
                        "<test>");
}

// The rows of the accesses' epochs, in order.
std::vector<PhaseRow> epoch_rows(const RunResult& r) {
  std::vector<PhaseRow> rows;
  for (const PhaseRow& p : r.timeline) {
    if (r.task_name(p).find("[epoch ") != std::string::npos) rows.push_back(p);
  }
  return rows;
}

const char* kRandomWhole = "pattern = \"random\"\nrequest = \"4 KiB\"\nadvice = \"random\"\nseed = 3\n";

TEST_CASE("random reads of a cached file hit every request, of an uncached one none, and read no more than asked", "[workload][access]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_scenario(with_accesses(profile, fmt::format("[[apps.tasks.access]]\nfile = \"hot\"\n{0}\n[[apps.tasks.access]]\nfile = "
                                                                        "\"cold\"\n{0}",
                                                                        kRandomWhole)));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 2);
    CHECK(r.task_name(e[0]) == "t:hot[epoch 1]");
    CHECK(r.task_name(e[1]) == "t:cold[epoch 1]");
    for (const PhaseRow& p : e) {
      CHECK(p.phase == PhaseKind::Read);
      CHECK(p.bytes == 8 * kMiB);
    }
    CHECK(e[0].cache_bytes == 8 * kMiB);
    CHECK(e[0].disk_bytes == 0);
    CHECK(e[1].cache_bytes == 0);
    CHECK(e[1].disk_bytes == 8 * kMiB);  // no readahead: each 4 KiB page once
    // Each of the 2048 misses one disk request.
    CHECK(e[1].end - e[1].start == Approx(2048 * (kLatency + 4096 / kDiskBw)).epsilon(0.01));
  }
}

TEST_CASE("random reads hit exactly the part of a file read before", "[workload][access]") {
  // The first half read in order (no readahead past it: advice random), then every page at random.
  const RunResult r = run_scenario(with_accesses(
      "linux", fmt::format("[[apps.tasks.access]]\nfile = \"cold\"\nlength = \"4 MiB\"\nrequest = \"1 MiB\"\nadvice = \"random\"\n"
                           "[[apps.tasks.access]]\nfile = \"cold\"\n{}repeat = 2",
                           kRandomWhole)));
  const std::vector<PhaseRow> e = epoch_rows(r);
  REQUIRE(e.size() == 3);
  CHECK(e[0].disk_bytes == 4 * kMiB);
  CHECK(e[1].cache_bytes == 4 * kMiB);  // the half read before, exactly
  CHECK(e[1].disk_bytes == 4 * kMiB);
  CHECK(r.task_name(e[2]) == "t:cold[epoch 2]");
  CHECK(e[2].cache_bytes == 8 * kMiB);  // all of it cached by now
}

TEST_CASE("a read after a write by range hits what was written, and only that", "[workload][access]") {
  const RunResult r = run_scenario(with_accesses(
      "linux", fmt::format("[[apps.tasks.access]]\nfile = \"cold\"\nmode = \"write\"\npattern = \"ranges\"\nranges = [[\"1 MiB\", \"2 MiB\"]]\n"
                           "request = \"256 KiB\"\n[[apps.tasks.access]]\nfile = \"cold\"\n{}",
                           kRandomWhole)));
  const std::vector<PhaseRow> e = epoch_rows(r);
  REQUIRE(e.size() == 2);
  CHECK(e[0].phase == PhaseKind::Write);
  CHECK(e[0].bytes == 2 * kMiB);
  CHECK(e[0].cache_bytes == 2 * kMiB);  // into the cache (writeback)
  CHECK(e[1].phase == PhaseKind::Read);
  CHECK(e[1].cache_bytes == 2 * kMiB);
  CHECK(e[1].disk_bytes == 6 * kMiB);
  CHECK(r.summary.write.bytes == 2 * kMiB);
  CHECK(r.summary.read.bytes == 8 * kMiB);
}

TEST_CASE("appends write the file from their offset, and a read after them finds it cached", "[workload][access]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_scenario(with_accesses(
        profile, "[[apps.tasks.access]]\nfile = \"cold\"\nmode = \"append\"\noffset = \"2 MiB\"\nrequest = \"100 kB\"\n"
                 "[[apps.tasks.access]]\nfile = \"cold\"\noffset = \"2 MiB\"\nrequest = \"1 MiB\"\n"));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 2);
    CHECK(e[0].phase == PhaseKind::Write);
    CHECK(e[0].bytes == 6 * kMiB);  // 62 appends of 100 kB, the last shorter
    CHECK(e[1].bytes == 6 * kMiB);
    CHECK(e[1].cache_bytes == 6 * kMiB);
    CHECK(e[1].disk_bytes == 0);
  }
}

TEST_CASE("a strided hyperslab that fits the cache is read from disk in epoch 1 and from memory in epoch 2", "[workload][access]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_scenario(with_accesses(
        profile, "[[apps.tasks.access]]\nfile = \"big\"\npattern = \"strided\"\nrequest = \"64 KiB\"\nstride = \"1 MiB\"\nrepeat = 2\n"));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 2);
    const std::int64_t slab = 64 * 64 * 1024;
    CHECK(r.task_name(e[1]) == "t:big[epoch 2]");
    CHECK(e[0].bytes == slab);
    CHECK(e[0].disk_bytes == slab);  // strided requests are not read ahead
    CHECK(e[0].end - e[0].start == Approx(64 * (kLatency + 65536 / kDiskBw)).epsilon(0.01));
    CHECK(e[1].cache_bytes == slab);
    CHECK(e[1].disk_bytes == 0);
    CHECK(e[1].end - e[1].start == Approx(static_cast<double>(slab) / kMemoryBw).epsilon(0.01));
  }
}

TEST_CASE("a seed fixes a random access's requests: the same run twice gives the same rows", "[workload][access]") {
  const std::string keys =
      "[[apps.tasks.access]]\nfile = \"big\"\npattern = \"random\"\nrequest = \"4 KiB\"\nreplacement = true\ncount = 3000\nseed = 11\nrepeat = 2";
  const RunResult a = run_scenario(with_accesses("linux", keys));
  const RunResult b = run_scenario(with_accesses("linux", keys));
  const std::vector<PhaseRow> ea = epoch_rows(a), eb = epoch_rows(b);
  REQUIRE(ea.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(ea[i].cache_bytes == eb[i].cache_bytes);
    CHECK(ea[i].end == eb[i].end);
  }
  CHECK(ea[1].cache_bytes > ea[0].cache_bytes);  // epoch 2 draws some of epoch 1's pages again
}

}  // namespace
namespace pagecache {
namespace {

TEST_CASE("a workflow task's access of one file runs on its host and reports its epochs", "[workload][access]") {
  const RunResult r = run_scenario(parse_scenario(R"([[hosts]]
name = "node"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "ssd"
read_bw = "500 MB/s"
write_bw = "400 MB/s"
[[files]]
name = "log"
size = "4 MiB"
[workflow]
name = "wf"
[[workflow.tasks]]
name = "writer"
[[workflow.tasks.access]]
file = "log"
mode = "append"
request = "64 KiB"
[[workflow.tasks]]
name = "reader"
after = ["writer"]
[[workflow.tasks.access]]
file = "log"
pattern = "random"
request = "64 KiB"
repeat = 2
)",
                                                  "<test>"));
  std::vector<PhaseRow> e;
  for (const PhaseRow& p : r.timeline) {
    if (r.task_name(p).find("[epoch ") != std::string::npos) e.push_back(p);
  }
  REQUIRE(e.size() == 3);
  CHECK(r.task_name(e[0]) == "writer:log[epoch 1]");
  CHECK(e[0].phase == PhaseKind::Write);
  CHECK(r.task_name(e[2]) == "reader:log[epoch 2]");
  for (const std::size_t i : {1, 2}) CHECK(e[i].cache_bytes == 4 * kMiB);  // the appended log, from the cache
}

TEST_CASE("invalidate drops the region's clean data before each epoch, as fio's invalidate=1 at each open", "[workload][access]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const char* kTwice = "[[apps.tasks.access]]\nfile = \"hot\"\nrequest = \"1 MiB\"\nrepeat = 2\n";
    const std::vector<PhaseRow> kept = epoch_rows(run_scenario(with_accesses(profile, kTwice)));
    REQUIRE(kept.size() == 2);
    for (const PhaseRow& e : kept) CHECK(e.cache_bytes == 8 * kMiB);  // cached at the start, and still
    const std::vector<PhaseRow> dropped = epoch_rows(run_scenario(with_accesses(profile, std::string(kTwice) + "invalidate = true\n")));
    REQUIRE(dropped.size() == 2);
    for (const PhaseRow& e : dropped) {
      CHECK(e.cache_bytes == 0);
      CHECK(e.disk_bytes == 8 * kMiB);
    }
  }
}

TEST_CASE("drop_after drops the region's clean data after each epoch: a read after it misses", "[workload][access]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const char* kTwice = "[[apps.tasks.access]]\nfile = \"hot\"\nrequest = \"1 MiB\"\nrepeat = 2\ndrop_after = true\n";
    const std::vector<PhaseRow> e = epoch_rows(run_scenario(with_accesses(profile, kTwice)));
    REQUIRE(e.size() == 2);
    CHECK(e[0].cache_bytes == 8 * kMiB);  // cached at the start
    CHECK(e[1].cache_bytes == 0);         // dropped after epoch 1
    CHECK(e[1].disk_bytes == 8 * kMiB);
  }
}

TEST_CASE("reshuffle = false repeats epoch 1's random requests every epoch, as fio's randrepeat", "[workload][access]") {
  // 1000 draws of 16384 pages: epoch 2 hits all of epoch 1's pages only if it draws the same.
  const char* kDraws = "[[apps.tasks.access]]\nfile = \"big\"\npattern = \"random\"\nrequest = \"4 KiB\"\nreplacement = true\n"
                       "count = 1000\nseed = 5\nrepeat = 2\n";
  const std::vector<PhaseRow> again = epoch_rows(run_scenario(with_accesses("linux", std::string(kDraws) + "reshuffle = false\n")));
  REQUIRE(again.size() == 2);
  CHECK(again[0].disk_bytes > 0);
  CHECK(again[1].disk_bytes == 0);
  CHECK(again[1].cache_bytes == again[1].bytes);
  const std::vector<PhaseRow> anew = epoch_rows(run_scenario(with_accesses("linux", kDraws)));
  REQUIRE(anew.size() == 2);
  CHECK(anew[1].disk_bytes > 0);
}

TEST_CASE("reshuffle is a key of random patterns, invalidate of accesses of one file", "[workload][access]") {
  CHECK_THROWS_WITH(with_accesses("linux", "[[apps.tasks.access]]\nfile = \"big\"\nreshuffle = false\n"),
                    Catch::Contains("reshuffle") && Catch::Contains("a key of pattern = \"random\""));
}

TEST_CASE("O_DIRECT by parts: each request a device request of its bytes; a write drops the stale cached pages", "[workload][access]") {
  // A task whose accesses are `accesses`, with direct_io.
  const auto direct = [](const std::string& accesses) {
    Scenario s = with_accesses("linux", accesses);
    s.apps[0].tasks[0].direct_io = true;
    return epoch_rows(run_scenario(std::move(s)));
  };
  // The cached file is read from the disk all the same, one 64 KiB request at a time:
  // 128 x (100 us + 64 KiB at 500 MB/s).
  const std::vector<PhaseRow> read = direct("[[apps.tasks.access]]\nfile = \"hot\"\nrequest = \"64 KiB\"\n");
  REQUIRE(read.size() == 1);
  CHECK(read[0].cache_bytes == 0);
  CHECK(read[0].disk_bytes == 8 * kMiB);
  CHECK(read[0].end - read[0].start == Approx(128 * (kLatency + 65536 / kDiskBw)).epsilon(1e-6));
  // A direct write over the cached file, then a buffered read of it: its pages were dropped.
  Scenario s = with_accesses("linux", "[[apps.tasks.access]]\nfile = \"hot\"\nmode = \"write\"\nrequest = \"1 MiB\"\n");
  s.apps[0].tasks[0].direct_io = true;
  TaskSpec reader;
  reader.name = "after";
  AccessSpec again;
  again.file = "hot";
  again.request = kMiB;
  again.length = 8 * kMiB;
  again.count = 8;
  reader.accesses.push_back(again);
  s.apps[0].tasks.push_back(reader);
  const std::vector<PhaseRow> rows = epoch_rows(run_scenario(std::move(s)));
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].disk_bytes == 8 * kMiB);
  CHECK(rows[1].cache_bytes == 0);
  CHECK(rows[1].disk_bytes == 8 * kMiB);
}

TEST_CASE("runtime stops an access's requests that long after it began, over its epochs (fio's runtime)", "[workload][access]") {
  // 64 MiB in 1 MiB requests takes about 0.14 s an epoch from the disk; 0.2 s stops epoch 2.
  const std::vector<PhaseRow> e = epoch_rows(run_scenario(with_accesses(
      "linux", "[[apps.tasks.access]]\nfile = \"big\"\nrequest = \"1 MiB\"\nrepeat = 5\ninvalidate = true\nruntime = \"0.2 s\"\n")));
  REQUIRE(e.size() == 2);  // epochs 3 to 5 never start
  CHECK(e[0].bytes == 64 * kMiB);
  CHECK(e[1].bytes < 64 * kMiB);
  CHECK(e[1].bytes > 0);
  // No request starts at or after the deadline: the last ends within one request of it.
  const double request = kLatency + kMiB / kDiskBw;
  CHECK(e[1].end >= e[0].start + 0.2);
  CHECK(e[1].end < e[0].start + 0.2 + 2 * request);
}

}  // namespace
}  // namespace pagecache

TEST_CASE("each byte of a phase is counted once, from the cache or the device, whatever the device read beyond it", "[workload][access]") {
  // A disk that reads ahead 128 KiB windows, read sequentially in 4 KiB requests; requests that
  // do not start on a page, read and written; a page's part written.
  const std::string accesses = R"([[apps.tasks.access]]
file = "cold"
request = "4 KiB"
repeat = 2
[[apps.tasks.access]]
file = "big"
pattern = "strided"
offset = "100 kB"
request = "50 kB"
stride = "500 kB"
[[apps.tasks.access]]
file = "hot"
mode = "write"
pattern = "strided"
request = "100 B"
stride = "1 MiB"
)";
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_scenario(with_accesses(profile, accesses, "read_ahead = \"128 KiB\""));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 4);
    for (const PhaseRow& row : e) {
      INFO(r.task_name(row));
      CHECK(row.cache_bytes + row.disk_bytes == row.bytes);
    }
    // The cold sequential read: every byte from the device, most of them read ahead of the
    // request that found them; the second epoch finds them all in the cache.
    CHECK(r.task_name(e[1]) == "t:cold[epoch 2]");
    CHECK(e[0].bytes == 8 * kMiB);
    CHECK(e[0].disk_bytes == 8 * kMiB);
    CHECK(e[1].cache_bytes == 8 * kMiB);
    // The strided reads: 134 requests of 50 kB, 13 or 14 pages each, all from the device (the
    // rest of their pages is read, and used by none).
    CHECK(e[2].bytes == 134 * 50'000);
    CHECK(e[2].disk_bytes == e[2].bytes);
    // Eight writes of 100 bytes into the cache, not eight pages.
    CHECK(e[3].bytes == 800);
    CHECK(e[3].cache_bytes == 800);
    // summary.json's figures are the rows'.
    CHECK(r.summary.cache_read_bytes + r.summary.disk_read_bytes == r.summary.read.bytes);
  }
}

}  // namespace pagecache
