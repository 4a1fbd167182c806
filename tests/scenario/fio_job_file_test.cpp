// The fio job file reader (src/formats/fio/job_file.hpp): syntax, values and options, one
// test per rule. Each expected value follows from fio 3.33's rules (parse.c, init.c, options.c)
// as stated in the comment, not from running the reader. Ordering, files, include and limits
// are in fio_job_order_test.cpp.

#include "fio_test_support.hpp"

#include <catch2/catch.hpp>

namespace pagecache::scenario {
using namespace pagecache::formats::fio;
namespace {

using testing::fio_error;
using testing::fio_read;

TEST_CASE("fio comments start at ';' or '#' anywhere on a line", "[fio]") {
  // init.c/parse.c: a line whose first character is ';' or '#' is skipped; elsewhere the line is
  // cut at the first ';' and then at the first '#', so no value can hold either.
  const FioJobFile f = fio_read("; a comment\n  # another\n[job] ; the job\nsize=64k ; note\nbs=8k# note\nfilename=a;b\n");
  REQUIRE(f.jobs.size() == 1);
  CHECK(f.jobs[0].section == "job");
  CHECK(f.jobs[0].size == 65536);
  CHECK(f.jobs[0].bs_read == 8192);
  CHECK(f.jobs[0].files == std::vector<std::string>{"a"});
}

TEST_CASE("fio sections named global* are global, others are jobs, names may repeat", "[fio]") {
  // strncmp(name, "global", 6): [global2] is global too; duplicate job names run as two jobs.
  const FioJobFile f = fio_read("[global2]\nsize=8k\n[a]\n[a]\n");
  REQUIRE(f.jobs.size() == 2);
  CHECK(f.jobs[0].name == "a");
  CHECK(f.jobs[1].name == "a");
  CHECK(f.jobs[1].size == 8192);
  CHECK(f.jobs[0].line == 3);
  CHECK(f.jobs[1].line == 4);
}

TEST_CASE("fio globals add up and apply only to the jobs after them", "[fio]") {
  // get_new_job copies the template as it stands at the job's header; later [global] sections
  // extend it; a job's own values never leak to the next job.
  const FioJobFile f = fio_read("[global]\nbs=8k\n[one]\nrw=write\n[global]\nsize=1m\n[two]\n");
  REQUIRE(f.jobs.size() == 2);
  CHECK(f.jobs[0].bs_read == 8192);
  CHECK(f.jobs[0].size == 0);
  CHECK(f.jobs[0].rw == FioRw::Write);
  CHECK(f.jobs[1].bs_read == 8192);
  CHECK(f.jobs[1].size == 1 << 20);
  CHECK(f.jobs[1].rw == FioRw::Read);
  CHECK(f.global_options == std::vector<std::pair<std::string, std::string>>{{"bs", "8k"}, {"size", "1m"}});
  CHECK(f.jobs[0].own_options == std::vector<std::pair<std::string, std::string>>{{"rw", "write"}});
  CHECK(f.jobs[1].own_options.empty());
}

TEST_CASE("fio name= renames a job for reports, not for its files, and is ignored in [global]", "[fio]") {
  // A job section overwrites an inherited name with its section name; $jobname is the section.
  const FioJobFile f = fio_read("[global]\nname=foo\n[job]\n[sec]\nname=bar\n");
  CHECK(f.jobs[0].name == "job");
  CHECK(f.jobs[1].name == "bar");
  CHECK(f.jobs[1].section == "sec");
  CHECK(f.jobs[1].files == std::vector<std::string>{"sec.0.0"});
}

TEST_CASE("fio defaults: psync, 4 KiB reads of section.0.0, invalidate, seed 0x89", "[fio]") {
  const FioJob j = fio_read("[j]\n").jobs.at(0);
  CHECK(j.rw == FioRw::Read);
  CHECK(j.bs_read == 4096);
  CHECK(j.bs_write == 4096);
  CHECK(j.files == std::vector<std::string>{"j.0.0"});
  CHECK_FALSE(j.files_given);
  CHECK(j.ioengine == "psync");
  CHECK(j.iodepth == 1);
  CHECK(j.invalidate);
  CHECK(j.randrepeat);
  CHECK(j.randseed == 0x89);
  CHECK(j.fadvise == FioFadvise::Auto);
  CHECK(j.loops == 1);
  CHECK(j.numjobs == 1);
  CHECK(j.rwmixread == 50);
  // fixup_options: a job that reads lays its files out with data (overwrite forced on).
  CHECK(j.overwrite);
  CHECK_FALSE(fio_read("[j]\nrw=write\n").jobs[0].overwrite);
}

TEST_CASE("fio sizes: k is 1024, KiB is 1000 under kb_base=1024, kb_base=1000 swaps them", "[fio]") {
  // bs=512: fio refuses a size below the block size.
  auto size = [](const std::string& value, const std::string& extra = "") {
    return fio_read("[j]\nbs=512\nsize=" + value + "\n" + extra).jobs[0].size;
  };
  CHECK(size("4k") == 4096);
  CHECK(size("4K") == 4096);
  CHECK(size("4kB") == 4096);
  CHECK(size("4KB") == 4096);
  CHECK(size("4KiB") == 4000);  // the 3-letter IEC forms take the opposite base
  CHECK(size("4kib") == 4000);
  CHECK(size("4ki") == 4096);   // "ki" is not "kib": fio's k rule
  CHECK(size("1m") == 1048576);
  CHECK(size("1MiB") == 1000000);
  CHECK(size("1g") == 1LL << 30);
  CHECK(size("1T") == 1LL << 40);
  CHECK(size("1p") == 1LL << 50);
  CHECK(size("4096b") == 4096);
  CHECK(size("0x1000") == 4096);
  CHECK(size("50%") == 0);
  CHECK(fio_read("[j]\nsize=50%\n").jobs[0].size_percent == 50);
  // kb_base is applied before every other option of its section (parse.c sort_options).
  CHECK(size("4k", "kb_base=1000\n") == 4000);
  CHECK(size("4KiB", "kb_base=1000\n") == 4096);
  CHECK(fio_read("[global]\nkb_base=1000\n[j]\nsize=1m\n").jobs[0].size == 1000000);
  // Integer options go through the same parser: iodepth=1k is 1024.
  CHECK(fio_read("[j]\niodepth=1k\n").jobs[0].iodepth == 1024);
}

TEST_CASE("fio sizes fio would misread are refused: fractions, unknown suffixes, negatives, over 100%", "[fio]") {
  // Deliberate differences: fio reads 1.5k as 1, 4x as 4, -1 as 2^64-1, 150% as a huge size.
  CHECK_THAT(fio_error("[j]\nsize=1.5k\n"), Catch::Contains("t.fio:2: option 'size=1.5k': fio reads no fractions"));
  CHECK_THAT(fio_error("[j]\nsize=4x\n"), Catch::Contains("unknown size suffix 'x'"));
  CHECK_THAT(fio_error("[j]\nsize=4kbytes\n"), Catch::Contains("unknown size suffix 'kbytes'"));
  CHECK_THAT(fio_error("[j]\nsize=-1\n"), Catch::Contains("negative"));
  CHECK_THAT(fio_error("[j]\nsize=150%\n"), Catch::Contains("from 1 to 100"));
  CHECK_THAT(fio_error("[j]\nsize=0%\n"), Catch::Contains("from 1 to 100"));
  CHECK_THAT(fio_error("[j]\nsize=99999999999999999999\n"), Catch::Contains("too large"));
  CHECK_THAT(fio_error("[j]\nsize=9000000p\n"), Catch::Contains("too large"));
  // size=4k-8k: fio keeps 4k and drops the rest without a word.
  CHECK_THAT(fio_error("[j]\nsize=4k-8k\n"), Catch::Contains("takes a single value"));
  CHECK_THAT(fio_error("[j]\nsize=\n"), Catch::Contains("option 'size' needs a value"));
  // init.c fixup_options: size below the block size is an error in fio too.
  CHECK_THAT(fio_error("[j]\nsize=2k\n"), Catch::Contains("t.fio:1: job 'j': size=2048 is smaller than the block size (4096"));
  // The smallest of the read, write and trim sizes counts, whatever the job does (fio.h
  // td_min_bs): with bs=8k,32k, the trim size stays 4096, so 4k is enough for a read job.
  CHECK(fio_read("[j]\nbs=8k,32k,\nsize=4k\n").jobs[0].size == 4096);
  CHECK_THAT(fio_error("[j]\nbs=8k,32k\nsize=4k\n"), Catch::Contains("smaller than the block size (8192"));
  CHECK_THAT(fio_error("[j]\nbs=0\n"), Catch::Contains("from 1 byte"));
}

TEST_CASE("fio times: runtime in seconds, thinktime in microseconds, us to days", "[fio]") {
  auto runtime = [](const std::string& value) { return fio_read("[j]\nruntime=" + value + "\n").jobs[0].runtime; };
  CHECK(runtime("10") == 10.0);
  CHECK(runtime("10s") == 10.0);
  CHECK(runtime("2m") == 120.0);  // m is minutes for times, never milli
  CHECK(runtime("1h") == 3600.0);
  CHECK(runtime("1d") == 86400.0);
  CHECK(runtime("500ms") == Approx(0.5));
  CHECK(runtime("500msec") == Approx(0.5));
  CHECK(runtime("250us") == Approx(250e-6));
  CHECK(runtime("250usec") == Approx(250e-6));
  CHECK(fio_read("[j]\ntimeout=7\n").jobs[0].runtime == 7.0);
  CHECK(fio_read("[j]\nthinktime=1000\n").jobs[0].thinktime == Approx(1e-3));
  CHECK(fio_read("[j]\nthinktime=5ms\n").jobs[0].thinktime == Approx(5e-3));
  CHECK(fio_read("[j]\nramp_time=3\n").jobs[0].ramp_time == 3.0);
  CHECK(fio_read("[j]\nstartdelay=4\n").jobs[0].startdelay == 4.0);
  // Deliberate differences: fio reads runtime=10sec as 10 us and 1.5ms as 1 s.
  CHECK_THAT(fio_error("[j]\nruntime=10sec\n"), Catch::Contains("unknown time suffix 'sec'") && Catch::Contains("10 microseconds"));
  CHECK_THAT(fio_error("[j]\nruntime=5min\n"), Catch::Contains("unknown time suffix 'min'"));
  CHECK_THAT(fio_error("[j]\nruntime=1.5ms\n"), Catch::Contains("fractions"));
  CHECK_THAT(fio_error("[j]\nstartdelay=0-10\n"), Catch::Contains("random start delay"));
}

TEST_CASE("fio bs splits into read and write sizes on ',' then ':' then '-'", "[fio]") {
  auto bs = [](const std::string& value, const std::string& before = "") {
    const FioJob j = fio_read(before + "[j]\nbs=" + value + "\n").jobs[0];
    return std::pair{j.bs_read, j.bs_write};
  };
  CHECK(bs("16k") == std::pair<std::int64_t, std::int64_t>{16384, 16384});
  CHECK(bs("8k,32k") == std::pair<std::int64_t, std::int64_t>{8192, 32768});
  CHECK(bs("8k,32k,") == std::pair<std::int64_t, std::int64_t>{8192, 32768});
  CHECK(bs(",8k") == std::pair<std::int64_t, std::int64_t>{4096, 8192});
  CHECK(bs("8k,") == std::pair<std::int64_t, std::int64_t>{8192, 4096});  // a trailing ',' keeps later slots
  CHECK(bs("4k-8k") == std::pair<std::int64_t, std::int64_t>{4096, 8192});  // not a range: bsrange is
  CHECK(bs("4k:8k") == std::pair<std::int64_t, std::int64_t>{4096, 8192});
  CHECK(bs("4k,8k,16k") == std::pair<std::int64_t, std::int64_t>{4096, 8192});
  // An empty piece keeps the inherited size.
  CHECK(bs(",16k", "[global]\nbs=8k\n") == std::pair<std::int64_t, std::int64_t>{8192, 16384});
  CHECK(fio_read("[j]\nblocksize=64k\n").jobs[0].bs_write == 65536);
  CHECK_THAT(fio_error("[j]\nbs=1k,2k,3k,4k\n"), Catch::Contains("at most three"));
}

TEST_CASE("fio rw modes and their :N", "[fio]") {
  CHECK(fio_read("[j]\nrw=randread\n").jobs[0].rw_step == 1);
  const FioJob random = fio_read("[j]\nrw=randread:8\n").jobs[0];
  CHECK(random.rw == FioRw::RandRead);
  CHECK(random.rw_step == 8);
  const FioJob backwards = fio_read("[j]\nreadwrite=read:-8k\n").jobs[0];
  CHECK(backwards.rw == FioRw::Read);
  CHECK(backwards.rw_step == -8192);
  CHECK(fio_read("[j]\nrw=readwrite\n").jobs[0].rw == FioRw::ReadWrite);
  CHECK(fio_read("[j]\nrw=randrw\nrwmixwrite=30\n").jobs[0].rwmixread == 70);
  CHECK(fio_read("[j]\nrw=randrw\nrwmixwrite=30\nrwmixread=80\n").jobs[0].rwmixread == 80);
  // str_rw_cb resets the step: an inherited :N does not survive a new rw=.
  CHECK(fio_read("[global]\nrw=randread:8\n[j]\nrw=randwrite\n").jobs[0].rw_step == 1);
  CHECK_THAT(fio_error("[j]\nrw=reed\n"), Catch::Contains("rw is one of read, write"));
  CHECK_THAT(fio_error("[j]\nrw=randtrim\n"), Catch::Contains("trims are not modelled"));
  CHECK_THAT(fio_error("[j]\nrw=randread:0\n"), Catch::Contains("at least 1"));
  CHECK_THAT(fio_error("[j]\nrwmixread=101\n"), Catch::Contains("from 0 to 100"));
}

TEST_CASE("fio bool options need 0 or 1, set-type flags may be bare", "[fio]") {
  CHECK(fio_read("[j]\ndirect=1\n").jobs[0].direct);
  CHECK_FALSE(fio_read("[j]\nbuffered=1\n").jobs[0].direct);
  CHECK(fio_read("[j]\nbuffered=0\n").jobs[0].direct);
  CHECK_THAT(fio_error("[j]\ndirect\n"), Catch::Contains("option 'direct' needs a value"));
  CHECK_THAT(fio_error("[j]\ndirect=2\n"), Catch::Contains("must be 0 or 1"));
  CHECK_THAT(fio_error("[j]\ndirect=true\n"), Catch::Contains("must be 0 or 1"));
  CHECK(fio_read("[j]\nnorandommap\n").jobs[0].norandommap);
  CHECK_FALSE(fio_read("[j]\nnorandommap=0\n").jobs[0].norandommap);
  CHECK(fio_read("[j]\ntime_based\nruntime=5\n").jobs[0].time_based);
  CHECK_THAT(fio_error("[j]\nnorandommap=yes\n"), Catch::Contains("whole number"));
}

TEST_CASE("fio options pcsim reads: syncs, loops, seeds, hints, engines", "[fio]") {
  const FioJob j = fio_read(
                       "[j]\nrw=write\nfsync=4\nfdatasync=2\nend_fsync=1\nfsync_on_close=1\nloops=3\nrandrepeat=0\nrandseed=42\n"
                       "fadvise_hint=sequential\nioengine=sync\ninvalidate=0\npre_read=1\ncreate_on_open=1\nunlink=1\n"
                       "offset=1m\noffset_increment=64k\nio_size=2m\nnumber_ios=10\nfilesize=8m\nthinktime_blocks=4\n"
                       "file_service_type=random:4\nsync=none\nrandom_distribution=random\n")
                       .jobs[0];
  CHECK(j.fsync == 4);
  CHECK(j.fdatasync == 2);
  CHECK(j.end_fsync);
  CHECK(j.fsync_on_close);
  CHECK(j.loops == 3);
  CHECK_FALSE(j.randrepeat);
  CHECK(j.randseed == 42);
  CHECK(j.randseed_given);
  CHECK(j.fadvise == FioFadvise::Sequential);
  CHECK(j.ioengine == "sync");
  CHECK_FALSE(j.invalidate);
  CHECK(j.pre_read);
  // init.c fixup_options: pre_read turns invalidate off.
  CHECK_FALSE(fio_read("[j]\npre_read=1\n").jobs[0].invalidate);
  CHECK(j.create_on_open);
  CHECK(j.unlink);
  CHECK(j.offset == 1 << 20);
  CHECK(j.offset_increment == 65536);
  CHECK(j.io_size == 2 << 20);
  CHECK(j.number_ios == 10);
  CHECK(j.filesize == 8 << 20);
  CHECK(j.thinktime_blocks == 4);
  CHECK(j.file_service == FioFileService::Random);
  CHECK(j.file_service_step == 4);
  CHECK(fio_read("[j]\nfadvise_hint=0\n").jobs[0].fadvise == FioFadvise::None);
  CHECK(fio_read("[j]\noffset=25%\n").jobs[0].offset_percent == 25);
  CHECK_THAT(fio_error("[j]\nfile_service_type=zipf:1.2\n"), Catch::Contains("not modelled"));
  CHECK_THAT(fio_error("[j]\nfilesize=1m-2m\n"), Catch::Contains("range of file sizes"));
  CHECK_THAT(fio_error("[j]\nloops=2000000000\n"), Catch::Contains("from 1 to 1000000000"));
}

TEST_CASE("fio options pcsim does not model are refused naming file, line and option", "[fio]") {
  CHECK_THAT(fio_error("[j]\nverify=crc32c\n"), Catch::Contains("t.fio:2: option 'verify' is not modelled by pcsim"));
  CHECK(testing::fio_place("[j]\nsize=4k\nbssplit=4k/50:8k/50\n").line == 3);
  CHECK(testing::fio_place("[j]\nsize=4k\nbssplit=4k/50:8k/50\n").key == "bssplit");
  CHECK_THAT(fio_error("[j]\nioengine=libaio\n"),
             Catch::Contains("t.fio:2: ioengine=libaio is not modelled: pcsim models one synchronous request at a time "
                             "(sync, psync, vsync, pvsync, pvsync2)"));
  CHECK_THAT(fio_error("[j]\nlockmem=1g\n"), Catch::Contains("pins memory"));
  CHECK_THAT(fio_error("[j]\nexitall\n"), Catch::Contains("ends other jobs early"));
  CHECK_THAT(fio_error("[j]\nsync=1\n"), Catch::Contains("not modelled"));
  CHECK_THAT(fio_error("[j]\nrandom_distribution=zipf:1.1\n"), Catch::Contains("not modelled"));
  CHECK_THAT(fio_error("[j]\nfilename=-\n"), Catch::Contains("standard input"));
  CHECK_THAT(fio_error("[j]\nhipri\n"), Catch::Contains("option 'hipri' is not modelled"));  // an engine's option
}

TEST_CASE("fio unknown options are refused, with the closest known name", "[fio]") {
  CHECK_THAT(fio_error("[j]\nioengin=psync\n"), Catch::Contains("unknown option 'ioengin'") && Catch::Contains("did you mean 'ioengine'?"));
  // Option names are case-sensitive in fio (o_match uses strcmp).
  CHECK_THAT(fio_error("[j]\nDirect=1\n"), Catch::Contains("unknown option 'Direct'") && Catch::Contains("did you mean 'direct'?"));
  CHECK_THAT(fio_error("[j]\nfrobnicate=1\n"), Catch::Contains("t.fio:2: unknown option 'frobnicate' (fio does not know it either)"));
}

TEST_CASE("fio lines fio would misread are refused: spaces around '=', bad headers", "[fio]") {
  // Deliberate difference: fio keeps the value's leading blank, so 'bs = 4k' is 4 bytes there.
  CHECK_THAT(fio_error("[j]\nbs = 4k\n"), Catch::Contains("t.fio:2: write 'bs=4k' without spaces around '='"));
  CHECK_THAT(fio_error("[j]\nrw= read\n"), Catch::Contains("write 'rw=read' without spaces"));
  CHECK_THAT(fio_error("size=4k\n[j]\n"), Catch::Contains("t.fio:1: option 'size' outside a job section"));
  CHECK_THAT(fio_error("[global]\nsize=4k\n"), Catch::Contains("no jobs defined"));
  CHECK_THAT(fio_error(""), Catch::Contains("no jobs defined"));
  CHECK_THAT(fio_error("[job\n"), Catch::Contains("must be '[name]'"));  // fio would name it "jo"
  CHECK_THAT(fio_error("[]\n"), Catch::Contains("must be '[name]'"));
  CHECK_THAT(fio_error("[j]\n=4k\n"), Catch::Contains("no option name"));
}

TEST_CASE("fio options that cannot change what pcsim computes are ignored with one warning each", "[fio]") {
  const FioJobFile f = fio_read("[global]\ngroup_reporting\nthread\n[a]\nthreads=1\ngroup_reporting\nwrite_bw_log=x\n[b]\niodepth=8\n"
                                "time_based\n");
  REQUIRE(f.warnings.size() == 6);
  CHECK_THAT(f.warnings[0], Catch::StartsWith("t.fio:2: option 'group_reporting' is ignored: it only changes fio's reports"));
  CHECK_THAT(f.warnings[1], Catch::StartsWith("t.fio:3: option 'thread' is ignored"));
  CHECK_THAT(f.warnings[2], Catch::Contains("t.fio:5: option 'threads' is ignored") && Catch::Contains("tiobench/act profiles"));
  CHECK_THAT(f.warnings[3], Catch::StartsWith("t.fio:7: option 'write_bw_log' is ignored"));
  // fio's own notes: the depth of a synchronous engine is 1; time_based needs a runtime.
  CHECK_THAT(f.warnings[4], Catch::Contains("t.fio:8: job 'b': time_based without runtime"));
  CHECK_THAT(f.warnings[5], Catch::Contains("iodepth=8") && Catch::Contains("caps it at 1"));
  CHECK_FALSE(f.jobs[1].time_based);
  CHECK(f.jobs[1].iodepth == 8);
  CHECK_THAT(fio_error("[j]\ngtod_reduce\n"), Catch::Contains("needs a value"));  // a bool, as in fio
}

TEST_CASE("fio ${VAR} takes the variable's value, or nothing when it is unset", "[fio]") {
  const FioJobFile f = fio_read("[j]\nsize=${SZ}\nfilename=${DIR}/f${UNSET}x\nname=a${b\n", {{"SZ", "64k"}, {"DIR", "/data"}});
  CHECK(f.jobs[0].size == 65536);
  CHECK(f.jobs[0].files == std::vector<std::string>{"/data/fx"});
  CHECK(f.jobs[0].name == "a${b");  // no closing brace: kept as written
  CHECK(f.jobs[0].own_options[0] == std::pair<std::string, std::string>{"size", "64k"});
  CHECK_THAT(fio_error("[j]\nnumjobs=$ncpus\n"), Catch::Contains("'$ncpus' stands for a figure of the machine"));
}

}  // namespace
}  // namespace pagecache::scenario
