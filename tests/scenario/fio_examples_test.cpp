// fio's own example jobs (package fio-examples: /usr/share/doc/fio/examples/, the examples/ of
// fio 3.33) through the fio job file reader. Each of the 86 files either reads, making the jobs
// fio makes (sections x numjobs), or is refused at the first option pcsim does not model, in the
// order fio applies them (sections in order; within one, kb_base first and filename last). The
// table is worked out from the files and fio's rules, not from running the reader.

#include "formats/fio/job_file.hpp"

#include "fio_property.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace pagecache::scenario {
using namespace pagecache::formats::fio;
namespace {

const std::filesystem::path kExamples = "/usr/share/doc/fio/examples";

struct Verdict {
  int jobs = 0;          // > 0: reads, making this many jobs
  const char* refused;   // else the option refused first
};

Verdict reads(int jobs) { return Verdict{jobs, ""}; }
Verdict refused(const char* option) { return Verdict{0, option}; }

// Most use an engine other than the synchronous ones, set before anything pcsim refuses.
const std::map<std::string, Verdict>& verdicts() {
  static const std::map<std::string, Verdict> kVerdicts{
      {"1mbs_clients.fio", refused("rate")},  // rate limits, before the 32 startdelay jobs
      {"aio-read.fio", refused("ioengine")},
      {"backwards-read.fio", reads(1)},
      {"basic-verify.fio", refused("ioengine")},
      {"butterfly.fio", refused("flow")},
      {"cmdprio-bssplit.fio", refused("ioengine")},
      {"cmdprio-percentage.fio", refused("ioengine")},
      {"cpp_null.fio", refused("ioengine")},
      {"cpuio.fio", refused("ioengine")},
      {"cross-stripe-verify.fio", refused("verify")},
      {"dedupe-global.fio", refused("ioengine")},
      {"dev-dax.fio", refused("ioengine")},
      {"dfs.fio", refused("ioengine")},
      {"disk-zone-profile.fio", refused("ioengine")},
      {"e4defrag.fio", refused("ioengine")},
      {"e4defrag2.fio", refused("ioengine")},
      {"enospc-pressure.fio", refused("ioengine")},
      {"exec.fio", refused("ioengine")},
      {"exitwhat.fio", refused("exitall")},
      {"falloc.fio", refused("ioengine")},
      {"filecreate-ioengine.fio", refused("ioengine")},
      {"filedelete-ioengine.fio", refused("ioengine")},
      {"filestat-ioengine.fio", refused("ioengine")},
      {"fio-rand-RW.fio", refused("ioengine")},
      {"fio-rand-read.fio", refused("ioengine")},
      {"fio-rand-write.fio", refused("ioengine")},
      {"fio-seq-RW.fio", refused("ioengine")},
      {"fio-seq-read.fio", refused("ioengine")},
      {"fio-seq-write.fio", refused("ioengine")},
      {"fixed-rate-submission.fio", refused("ioengine")},
      {"flow.fio", refused("ioengine")},
      {"fsx.fio", refused("ioengine")},
      {"ftruncate.fio", refused("ioengine")},
      {"gfapi.fio", refused("ioengine")},
      {"gpudirect-rdmaio-client.fio", refused("ioengine")},
      {"gpudirect-rdmaio-server.fio", refused("ioengine")},
      {"http-s3-crypto.fio", refused("ioengine")},
      {"http-s3-storage-class.fio", refused("ioengine")},
      {"http-s3.fio", refused("ioengine")},
      {"http-swift.fio", refused("ioengine")},
      {"http-webdav.fio", refused("ioengine")},
      {"ime.fio", refused("iodepth_batch")},  // its engines are set in the job sections
      {"iometer-file-access-server.fio", refused("bssplit")},
      {"jesd219.fio", refused("ioengine")},
      {"latency-profile.fio", refused("random_generator")},
      {"libcufile-cufile.fio", refused("ioengine")},
      {"libcufile-posix.fio", refused("ioengine")},
      {"libhdfs.fio", refused("ioengine")},
      {"libiscsi.fio", refused("ioengine")},
      {"libpmem.fio", refused("ioengine")},
      {"librpma_apm-client.fio", refused("ioengine")},
      {"librpma_apm-server.fio", refused("ioengine")},
      {"librpma_gpspm-client.fio", refused("ioengine")},
      {"librpma_gpspm-server.fio", refused("ioengine")},
      {"libzbc-rand-write.fio", refused("zonemode")},
      {"libzbc-seq-read.fio", refused("zonemode")},
      {"mtd.fio", refused("ioengine")},
      {"nbd.fio", refused("ioengine")},
      {"netio.fio", refused("ioengine")},
      {"netio_multicast.fio", refused("ioengine")},
      {"nfs.fio", refused("nfs_url")},  // the nfs engine's own option, before ioengine=nfs
      {"null.fio", refused("ioengine")},
      {"numa.fio", refused("ioengine")},
      {"pmemblk.fio", refused("ioengine")},
      {"poisson-rate-submission.fio", refused("ioengine")},
      {"rados.fio", refused("ioengine")},
      {"rand-zones.fio", refused("random_distribution")},  // zoned:...
      {"rbd.fio", refused("ioengine")},
      {"rdmaio-client.fio", refused("ioengine")},
      {"rdmaio-server.fio", refused("ioengine")},
      {"sg_verify-fail.fio", refused("ioengine")},
      {"sg_verify.fio", refused("ioengine")},
      {"sg_write_same_ndob.fio", refused("ioengine")},
      {"ssd-steadystate.fio", refused("ioengine")},
      {"ssd-test.fio", refused("ioengine")},
      {"steadystate.fio", refused("ss")},  // before its filename=/dev/null, applied last
      {"surface-scan.fio", refused("verify")},
      {"tiobench-example.fio", reads(16)},  // 4 sections x numjobs=4; bsrange=4k-4k is bs=4k
      {"uring-cmd-ng.fio", refused("ioengine")},
      {"uring-cmd-zoned.fio", refused("ioengine")},
      {"waitfor.fio", reads(16)},  // 4 sections x numjobs=4
      {"xnvme-compare.fio", refused("allow_file_create")},
      {"xnvme-zoned.fio", refused("zonemode")},
      {"zbd-rand-write.fio", refused("zonemode")},
      {"zbd-seq-read.fio", refused("zonemode")},
      {"zipf.fio", refused("ioengine")},
  };
  return kVerdicts;
}

TEST_CASE("fio's 86 example jobs read or are refused at the option the table names", "[fio]") {
  // CI runs scripts/install-deps first, which installs fio-examples: a missing folder is a
  // broken setup, not a reason to skip.
  INFO("install fio's examples with scripts/install-deps (package fio-examples)");
  REQUIRE(std::filesystem::is_directory(kExamples));
  std::map<std::string, bool> seen;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".fio") continue;
    const std::string name = entry.path().filename().string();
    INFO(name);
    REQUIRE(verdicts().count(name) == 1);
    const Verdict& expected = verdicts().at(name);
    seen[name] = true;
    try {
      const FioJobFile f = read_fio_job_file(entry.path().string());
      CHECK(static_cast<int>(f.jobs.size()) == expected.jobs);
    } catch (const ConfigError& error) {
      INFO(error.what());
      CHECK(expected.jobs == 0);
      CHECK(error.place().key == expected.refused);
    }
  }
  CHECK(seen.size() == 86);
}

TEST_CASE("fio's waitfor.fio: shared file, wait_for chains, new groups", "[fio]") {
  REQUIRE(std::filesystem::is_directory(kExamples));
  const FioJobFile f = read_fio_job_file((kExamples / "waitfor.fio").string());
  REQUIRE(f.jobs.size() == 16);
  for (std::size_t i = 0; i < 16; ++i) {
    INFO(i);
    CHECK(f.jobs[i].files == std::vector<std::string>{"/tmp/data"});
    CHECK(f.jobs[i].filesize == 128 << 20);
    CHECK(f.jobs[i].runtime == 10.0);
    CHECK(f.jobs[i].group == static_cast<int>(i / 4));
    std::vector<std::size_t> after;
    for (std::size_t k = 0; k < 4 && i >= 4; ++k) after.push_back(i / 4 * 4 - 4 + k);
    CHECK(f.jobs[i].after == after);
  }
  CHECK(f.jobs[0].bs_write == 128 << 10);
  CHECK(f.jobs[4].rw == FioRw::RandRead);
  CHECK(f.jobs[8].rw == FioRw::RandWrite);
}

TEST_CASE("fio's tiobench-example.fio: four stonewalled phases of four clones", "[fio]") {
  REQUIRE(std::filesystem::is_directory(kExamples));
  const FioJobFile f = read_fio_job_file((kExamples / "tiobench-example.fio").string());
  REQUIRE(f.jobs.size() == 16);
  CHECK(f.jobs[1].files == std::vector<std::string>{"f1.3.0"});
  CHECK(f.jobs[4].files == std::vector<std::string>{"f2.0.0"});
  CHECK(f.jobs[12].after.size() == 12);
  CHECK(f.jobs[13].after.size() == 12);
  CHECK(f.jobs[4].group == 1);
  CHECK(f.jobs[15].group == 3);
  CHECK(f.jobs[0].direct);
  CHECK(f.jobs[0].size == 512 << 20);
  CHECK(f.jobs[0].runtime == 60.0);
  CHECK(f.jobs[0].bs_read == 4096);
}

TEST_CASE("fio's backwards-read.fio: reads backwards through a file named 128m", "[fio]") {
  REQUIRE(std::filesystem::is_directory(kExamples));
  const FioJob j = read_fio_job_file((kExamples / "backwards-read.fio").string()).jobs.at(0);
  CHECK(j.files == std::vector<std::string>{"128m"});
  CHECK(j.rw_step == -8192);
  CHECK(j.size == 128 << 20);
}

TEST_CASE("fio's examples and the fuzz seeds keep the reader's contract", "[fio]") {
  // fuzz/fio_property.hpp: read and keep the promises, or refused with ConfigError.
  REQUIRE(std::filesystem::is_directory(kExamples));
  int files = 0;
  for (const std::filesystem::path& dir : {kExamples, std::filesystem::path(PAGECACHE_FUZZ_SEEDS_DIR)}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".fio") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      INFO(entry.path().string());
      CHECK(fuzz::check_fio_text(text, entry.path().string()).empty());
      ++files;
    }
  }
  CHECK(files >= 86 + 3);
}

TEST_CASE("fio's seeds read as their comments say", "[fio]") {
  // fio-clones-order.fio: 3 writers sharing two files, 2 readers behind a stonewall, one job
  // renamed tail waiting for the writers.
  const FioJobFile f = read_fio_job_file(std::string(PAGECACHE_FUZZ_SEEDS_DIR) + "/fio-clones-order.fio");
  REQUIRE(f.jobs.size() == 6);
  CHECK(f.jobs[0].files == std::vector<std::string>{"/tmp/shared:a", "/tmp/b"});
  CHECK(f.jobs[3].files == std::vector<std::string>{"d1/readers.0.0"});
  CHECK(f.jobs[4].files == std::vector<std::string>{"d2/readers.1.0"});
  CHECK(f.jobs[3].rw_step == 4);
  CHECK(f.jobs[5].name == "tail");
  CHECK(f.jobs[5].after == std::vector<std::size_t>{0, 1, 2});
  CHECK(f.jobs[5].group == 2);
  CHECK(f.jobs[3].bs_write == 16384);
}

}  // namespace
}  // namespace pagecache::scenario
