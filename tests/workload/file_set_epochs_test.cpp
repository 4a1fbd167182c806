// Epochs over a file set, run: a data set that fits the page cache is read from memory from
// epoch 2 on; one 1.2x larger is read from disk again by sequential epochs (LRU's worst case:
// each file is evicted before its turn comes back) and only in part from the cache by shuffled
// ones; each epoch without replacement reads every file once; a seed fixes the orders.

#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "support/unchecked_runs.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pagecache {
namespace {

// 1 GB of memory copied at 10 GB/s, a disk read at 500 MB/s; `count` files of 100 kB, so that
// 10,000 files are the memory's size.
constexpr double kMemoryBw = 10e9;
constexpr double kDiskBw = 500e6;
constexpr std::int64_t kFile = 100'000;

Scenario epochs(const std::string& profile, std::int64_t count, const std::string& access) {
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
[[file_sets]]
name = "images"
count = {}
size = "100 kB"
[[apps]]
name = "trainer"
[[apps.tasks]]
name = "train"
[[apps.tasks.access]]
files = "images"
{}
)",
                                    profile, count, access),
                        "<test>");
}

// Tens of thousands of file reads: a debug build's check after each operation would walk
// every file's blocks each time (test::UncheckedRuns).
RunResult run_unchecked(const Scenario& s) {
  const test::UncheckedRuns unchecked;
  return run_scenario(s);
}

// The timeline's rows of the epochs, in order (the task's own read, compute and write left out).
std::vector<PhaseRow> epoch_rows(const RunResult& r) {
  std::vector<PhaseRow> rows;
  for (const PhaseRow& p : r.timeline) {
    if (r.task_name(p).find("[epoch ") != std::string::npos) rows.push_back(p);
  }
  return rows;
}

TEST_CASE("a data set at 0.8x memory is read from disk once, then from the page cache", "[workload][file_sets]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_unchecked(epochs(profile, 8000, "pattern = \"random\"\nseed = 1\nrepeat = 3"));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 3);
    CHECK(r.task_name(e[0]) == "train:images[epoch 1]");
    CHECK(r.task_name(e[2]) == "train:images[epoch 3]");
    const std::int64_t bytes = 8000 * kFile;
    for (const PhaseRow& p : e) CHECK(p.bytes == bytes);
    CHECK(e[0].disk_bytes == bytes);
    CHECK(e[0].end - e[0].start == Approx(static_cast<double>(bytes) / kDiskBw));  // 1.6 s
    for (const std::size_t i : {1, 2}) {
      CHECK(e[i].cache_bytes == bytes);
      CHECK(e[i].end - e[i].start == Approx(static_cast<double>(bytes) / kMemoryBw));  // 0.08 s
    }
    CHECK(r.summary.read.bytes == 3 * bytes);
  }
}

TEST_CASE("a data set at 1.2x memory read in order comes from disk every epoch (LRU thrashing)", "[workload][file_sets]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_unchecked(epochs(profile, 12'000, "repeat = 2"));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 2);
    const std::int64_t bytes = 12'000 * kFile;
    // The first 10,000 files fill the cache; each next one evicts the oldest, so file k is gone
    // when epoch 2 comes back to it: every byte from disk, at the disk's rate.
    CHECK(e[1].disk_bytes == bytes);
    CHECK(e[1].cache_bytes == 0);
    CHECK(e[1].end - e[1].start == Approx(static_cast<double>(bytes) / kDiskBw));  // 2.4 s
  }
}

TEST_CASE("a data set at 1.2x memory read shuffled finds part of epoch 2 in the cache, less than it holds", "[workload][file_sets]") {
  for (const char* profile : {"linux", "paper"}) {
    INFO(profile);
    const RunResult r = run_unchecked(epochs(profile, 12'000, "pattern = \"random\"\nseed = 42\nrepeat = 2"));
    const std::vector<PhaseRow> e = epoch_rows(r);
    REQUIRE(e.size() == 2);
    // Epoch 2 starts with at most the memory's 10,000 files of 12,000 cached, and each miss
    // evicts one of those not yet read again: its hits are fewer than 1/1.2 of its bytes, but
    // not none (a random order reaches many cached files before they are evicted).
    const double share = static_cast<double>(e[1].cache_bytes) / static_cast<double>(e[1].bytes);
    CHECK(share > 0.2);
    CHECK(share < 1.0 / 1.2);
    CHECK(e[1].cache_bytes + e[1].disk_bytes == e[1].bytes);
    // Hits make the epoch shorter than a read from disk alone, longer than from memory alone.
    CHECK(e[1].end - e[1].start < static_cast<double>(e[1].bytes) / kDiskBw);
    CHECK(e[1].end - e[1].start > static_cast<double>(e[1].bytes) / kMemoryBw);
  }
}

TEST_CASE("each epoch without replacement reads every file of the set once", "[workload][file_sets]") {
  // At 0.5x nothing is evicted: after epoch 1, a file read is wholly cached, one not read is not.
  const RunResult r = run_unchecked(epochs("linux", 5000, "pattern = \"random\"\nseed = 9"));
  const std::vector<PhaseRow> e = epoch_rows(r);
  REQUIRE(e.size() == 1);
  CHECK(e[0].bytes == 5000 * kFile);  // 5,000 reads of a whole file
  REQUIRE(r.cache_not_recorded.empty());
  std::uint32_t row = 0;
  while (r.task_name(r.timeline[row]).find("[epoch 1]") == std::string::npos) ++row;
  int whole = 0, cached_files = 0;
  for (const CacheRow& c : r.cache) {
    if (c.phase != row || r.files[c.file].rfind("images/", 0) != 0) continue;
    ++cached_files;
    whole += c.cached == kFile ? 1 : 0;
  }
  CHECK(cached_files == 5000);
  CHECK(whole == 5000);  // so each of the 5,000 reads was of another file
}

TEST_CASE("with replacement, an epoch's draws repeat some files and leave others unread", "[workload][file_sets]") {
  const RunResult r = run_unchecked(epochs("linux", 5000, "pattern = \"random\"\nreplacement = true\nseed = 9"));
  const std::vector<PhaseRow> e = epoch_rows(r);
  REQUIRE(e.size() == 1);
  CHECK(e[0].bytes == 5000 * kFile);
  // 5,000 draws of 5,000 files leave about 5000 / e = 1,839 unread; a repeated file is a hit.
  const double unread_share = 1.0 - static_cast<double>(e[0].disk_bytes) / static_cast<double>(e[0].bytes);
  CHECK(unread_share == Approx(1839.0 / 5000.0).margin(0.03));
  CHECK(e[0].cache_bytes > 0);
}

TEST_CASE("the same seed gives the same run, another seed another", "[workload][file_sets]") {
  const auto epoch2 = [](int seed) {
    const RunResult r = run_unchecked(epochs("linux", 12'000, fmt::format("pattern = \"random\"\nseed = {}\nrepeat = 2", seed)));
    return epoch_rows(r).at(1).cache_bytes;
  };
  CHECK(epoch2(5) == epoch2(5));
  CHECK(epoch2(5) != epoch2(6));
}

TEST_CASE("a workflow task reads a file set of another host over its link, and caches it", "[workload][file_sets]") {
  const RunResult r = run_unchecked(parse_scenario(R"(
[[hosts]]
name = "client"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "local"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[hosts]]
name = "storage"
memory = "1 GB"
memory_read_bw = "10 GB/s"
memory_write_bw = "10 GB/s"
[[hosts.disks]]
name = "raid"
read_bw = "500 MB/s"
write_bw = "500 MB/s"
[[links]]
name = "net"
bandwidth = "100 MB/s"
latency = "0 s"
hosts = ["client", "storage"]
[[file_sets]]
name = "shards"
count = 10
size = "10 MB"
host = "storage"
[workflow]
host = "client"
[[workflow.tasks]]
name = "fit"
[[workflow.tasks.access]]
files = "shards"
repeat = 2
)",
                                                  "<test>"));
  const std::vector<PhaseRow> e = epoch_rows(r);
  REQUIRE(e.size() == 2);
  CHECK(r.task_name(e[0]) == "fit:shards[epoch 1]");
  CHECK(e[0].end - e[0].start == Approx(100e6 / 100e6));  // through the 100 MB/s link
  CHECK(e[1].cache_bytes == 100'000'000);                 // the client's own cache
}

}  // namespace
}  // namespace pagecache
