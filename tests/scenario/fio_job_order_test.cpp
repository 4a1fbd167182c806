// The fio job file reader (src/formats/fio/job_file.hpp): clones, files, groups and start
// order, include, and hostile limits. Each expected value follows from fio 3.33's rules (init.c
// add_job, get_new_job, wait_for_ok; options.c get_next_str, set_name_idx; backend.c
// run_threads) as stated in the comment, not from running the reader.

#include "fio_test_support.hpp"
#include "support/files.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>

namespace pagecache::scenario {
using namespace pagecache::formats::fio;
namespace {

using testing::fio_error;
using testing::fio_read;
using Files = std::vector<std::string>;
using After = std::vector<std::size_t>;

TEST_CASE("fio numjobs clones follow their job as jobnum 0, N-1 ... 1 with their own files", "[fio]") {
  const FioJobFile f = fio_read("[j]\nnumjobs=3\nsize=4k\n[k]\n");
  REQUIRE(f.jobs.size() == 4);
  CHECK(f.jobs[0].jobnum == 0);
  CHECK(f.jobs[1].jobnum == 2);
  CHECK(f.jobs[2].jobnum == 1);
  CHECK(f.jobs[0].files == Files{"j.0.0"});
  CHECK(f.jobs[1].files == Files{"j.2.0"});
  CHECK(f.jobs[2].files == Files{"j.1.0"});
  for (int i = 0; i < 3; ++i) {
    CHECK(f.jobs[i].name == "j");
    CHECK(f.jobs[i].numjobs == 3);
    CHECK(f.jobs[i].size == 4096);
  }
  // jobnum is the clone index, not a job count: another section starts at .0 again.
  CHECK(f.jobs[3].files == Files{"k.0.0"});
}

TEST_CASE("fio clones share a given filename", "[fio]") {
  const FioJobFile f = fio_read("[j]\nnumjobs=2\nfilename=/tmp/data\n");
  REQUIRE(f.jobs.size() == 2);
  CHECK(f.jobs[0].files == Files{"/tmp/data"});
  CHECK(f.jobs[1].files == Files{"/tmp/data"});
  CHECK(f.jobs[1].files_given);
}

TEST_CASE("fio filename accumulates: global and job files, repeated lines, nrfiles ignored", "[fio]") {
  CHECK(fio_read("[global]\nfilename=a\n[j]\nfilename=b\n").jobs[0].files == Files{"a", "b"});
  CHECK(fio_read("[j]\nfilename=x\nfilename=y\nnrfiles=3\n").jobs[0].files == Files{"x", "y"});
  CHECK(fio_read("[j]\nnrfiles=2\n").jobs[0].files == Files{"j.0.0", "j.0.1"});
  CHECK(fio_read("[j]\nnr_files=2\nnumjobs=2\n").jobs[1].files == Files{"j.1.0", "j.1.1"});
}

TEST_CASE("fio filename lists split on ':' with '\\:' for a colon, empty entries skipped", "[fio]") {
  CHECK(fio_read("[j]\nfilename=x\\:2:y\n").jobs[0].files == Files{"x:2", "y"});
  CHECK(fio_read("[j]\nfilename=:a::b:\n").jobs[0].files == Files{"a", "b"});
}

TEST_CASE("fio directory prefixes files: generated ones by jobnum mod folders, given ones the first", "[fio]") {
  const FioJobFile generated = fio_read("[j]\ndirectory=d1:d2\nnumjobs=3\n");
  CHECK(generated.jobs[0].files == Files{"d1/j.0.0"});
  CHECK(generated.jobs[1].files == Files{"d1/j.2.0"});  // 2 mod 2 = 0
  CHECK(generated.jobs[2].files == Files{"d2/j.1.0"});
  // filename is applied after directory (parse.c sort_options), with jobnum 0: the first folder.
  CHECK(fio_read("[j]\nfilename=f\ndirectory=d1:d2\nnumjobs=2\n").jobs[1].files == Files{"d1/f"});
  // Even an absolute name is prefixed, by plain concatenation.
  CHECK(fio_read("[j]\ndirectory=/d\nfilename=/abs\n").jobs[0].files == Files{"/d//abs"});
  // An inherited file keeps the folder it was given with.
  CHECK(fio_read("[global]\nfilename=g\n[j]\ndirectory=d\nfilename=f\n").jobs[0].files == Files{"g", "d/f"});
}

TEST_CASE("fio filename_format names generated files, its keywords in any case", "[fio]") {
  const FioJobFile f = fio_read("[j]\nfilename_format=$jobname-$JOBNUM/f$filenum\nnumjobs=2\nnrfiles=2\n");
  CHECK(f.jobs[0].files == Files{"j-0/f0", "j-0/f1"});
  CHECK(f.jobs[1].files == Files{"j-1/f0", "j-1/f1"});
}

TEST_CASE("fio stonewall holds a job and every later one until all earlier jobs end", "[fio]") {
  // run_threads stops starting jobs at a stonewall until everything started has exited; a
  // stonewall starts a new reporting group if the previous one has jobs; clones drop stonewall.
  const FioJobFile f = fio_read("[a]\nstonewall\nnumjobs=2\n[b]\nstonewall\nnumjobs=2\n[c]\n[d]\nnew_group\n");
  REQUIRE(f.jobs.size() == 6);
  CHECK(f.jobs[0].after.empty());
  CHECK(f.jobs[1].after.empty());
  CHECK(f.jobs[2].after == After{0, 1});
  CHECK(f.jobs[3].after == After{0, 1});
  CHECK(f.jobs[4].after == After{0, 1});
  CHECK(f.jobs[5].after == After{0, 1});
  const std::vector<int> groups{f.jobs[0].group, f.jobs[1].group, f.jobs[2].group, f.jobs[3].group, f.jobs[4].group, f.jobs[5].group};
  CHECK(groups == std::vector<int>{0, 0, 1, 1, 1, 2});  // the first job's stonewall finds group 0 empty
  CHECK(fio_read("[a]\n[b]\nwait_for_previous\n").jobs[1].after == After{0});
}

TEST_CASE("fio wait_for holds a job until the named job and its clones end", "[fio]") {
  const FioJobFile f = fio_read("[w]\nnumjobs=2\n[r]\nwait_for=w\n[x]\n[sec]\nname=writer\n[y]\nwait_for=writer\n");
  CHECK(f.jobs[2].after == After{0, 1});
  CHECK(f.jobs[3].after.empty());  // wait_for holds no later job
  CHECK(f.jobs[5].after == After{4});  // matched by the reported name
  CHECK(f.jobs[2].group == 0);
}

TEST_CASE("fio wait_for must name one earlier job other than itself", "[fio]") {
  CHECK_THAT(fio_error("[a]\n[r]\nwait_for=nosuch\n"), Catch::Contains("t.fio:2: job 'r': wait_for=nosuch names no job defined before it"));
  CHECK_THAT(fio_error("[r]\nwait_for=w\n[w]\n"), Catch::Contains("names no job defined before it"));
  CHECK_THAT(fio_error("[a]\nwait_for=a\n"), Catch::Contains("cannot wait for itself"));
  CHECK_THAT(fio_error("[w]\n[w]\n[r]\nwait_for=w\n"), Catch::Contains("ambiguous: 2 jobs"));
}

TEST_CASE("fio include reads a file relative to the including one, nested, into the section", "[fio]") {
  const auto dir = pagecache::testing::scratch("fio-include");
  std::filesystem::create_directories(dir / "sub");
  std::ofstream(dir / "main.fio") << "[global]\ninclude common.fio\n[j]\ninclude sub/job.fio\n";
  std::ofstream(dir / "common.fio") << "bs=8k\n";
  std::ofstream(dir / "sub" / "job.fio") << "size=1m\ninclude deeper.fio\n";
  std::ofstream(dir / "sub" / "deeper.fio") << "rw=randread\n";
  const FioJobFile f = read_fio_job_file((dir / "main.fio").string());
  REQUIRE(f.jobs.size() == 1);
  CHECK(f.jobs[0].bs_read == 8192);
  CHECK(f.jobs[0].size == 1 << 20);
  CHECK(f.jobs[0].rw == FioRw::RandRead);
  CHECK(f.global_options == std::vector<std::pair<std::string, std::string>>{{"bs", "8k"}});
}

TEST_CASE("a line of an included file is named by its place and option name, its text never quoted", "[fio]") {
  // The included file is anyone's: /etc/passwd, a file of secrets.
  const auto dir = pagecache::testing::scratch("fio-include-foreign");
  const auto error = [&](const std::string& included) -> std::string {
    std::ofstream(dir / "foreign") << included;
    std::ofstream(dir / "main.fio") << "[j]\nsize=1m\ninclude " << (dir / "foreign").string() << "\n";
    try {
      read_fio_job_file((dir / "main.fio").string());
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string passwd = error("root:x:0:0:root:/root:/bin/bash\n");
  CHECK_THAT(passwd, Catch::Contains("foreign:1: not an option line of a fio job file") && !Catch::Contains("root"));
  const std::string spaced = error("PASSWORD = hunter2\n");
  CHECK_THAT(spaced, Catch::Contains("foreign:1: write option 'PASSWORD' without spaces around '='") && !Catch::Contains("hunter2"));
  const std::string unknown = error("token=hunter2\n");
  CHECK_THAT(unknown, Catch::Contains("foreign:1: unknown option 'token'") && !Catch::Contains("hunter2"));
  const std::string bad_value = error("size=hunter2\n");
  CHECK_THAT(bad_value, Catch::Contains("foreign:1: option 'size'") && !Catch::Contains("hunter2"));
  // The job file itself is the user's own: its values are quoted, as they help.
  CHECK_THAT(fio_error("[j]\nsize=lots\n"), Catch::Contains("option 'size=lots'"));
  // A line that is no option, in the job file too, is not quoted: it may be another file's.
  CHECK_THAT(fio_error("root:x:0:0:root:/root:/bin/bash\n[j]\n"), Catch::Contains("t.fio:1: neither a [section] header nor an option line") &&
                                                                    !Catch::Contains("root"));
}

TEST_CASE("fio include refuses cycles, sections in included files, and missing files", "[fio]") {
  const auto dir = pagecache::testing::scratch("fio-include-bad");
  std::ofstream(dir / "a.fio") << "[j]\ninclude b.fio\n";
  std::ofstream(dir / "b.fio") << "size=4k\ninclude a.fio\n";
  std::ofstream(dir / "section.fio") << "[j]\ninclude new.fio\n";
  std::ofstream(dir / "new.fio") << "[x]\n";
  std::ofstream(dir / "missing.fio") << "[j]\ninclude nowhere.fio\n";
  auto error = [&](const char* name) {
    try {
      read_fio_job_file((dir / name).string());
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(read without error)");
  };
  CHECK_THAT(error("a.fio"), Catch::Contains("b.fio:2: include 'a.fio' includes itself (a cycle)"));
  CHECK_THAT(error("section.fio"), Catch::Contains("new.fio:1: an included file cannot open a new section"));
  CHECK_THAT(error("missing.fio"), Catch::Contains("missing.fio:2: cannot include 'nowhere.fio'"));
  CHECK_THAT(fio_error("include x.fio\n[j]\n"), Catch::Contains("outside a job section"));
}

TEST_CASE("fio include chains deeper than the limit are refused", "[fio]") {
  const auto dir = pagecache::testing::scratch("fio-include-deep");
  std::ofstream(dir / "top.fio") << "[j]\ninclude 0.fio\n";
  for (int i = 0; i < 20; ++i) std::ofstream(dir / (std::to_string(i) + ".fio")) << "include " << i + 1 << ".fio\n";
  std::ofstream(dir / "20.fio") << "size=4k\n";
  CHECK_THROWS_WITH(read_fio_job_file((dir / "top.fio").string()), Catch::Contains("includes nest deeper than 16"));
}

TEST_CASE("fio hostile job files are refused fast, naming the limit", "[fio]") {
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(fio_error("[j]\nnumjobs=1000000000\n"), Catch::Contains("from 1 to 100000"));
  CHECK_THAT(fio_error("[a]\nnumjobs=60000\n[b]\nnumjobs=60000\n"), Catch::Contains("more than 100000 jobs in all"));
  CHECK_THAT(fio_error("[j]\nnrfiles=100000000\n"), Catch::Contains("more than the 2000000 files a run may have"));
  CHECK_THAT(fio_error("[j]\nnumjobs=50000\nnrfiles=1000\n"), Catch::Contains("more than 20000000 file names"));
  // stonewalls after many clones: each later job lists every earlier one.
  CHECK_THAT(fio_error("[a]\nnumjobs=50000\n[b]\nstonewall\nnumjobs=50000\n"), Catch::Contains("orderings"));
  CHECK_THAT(fio_error("[j]\nname=" + std::string(9000, 'x') + "\n"), Catch::Contains("longer than fio's 8191 bytes"));
  CHECK_THAT(fio_error(std::string("[j]\nname=a\0b\n", 13)), Catch::Contains("NUL byte"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}

}  // namespace
}  // namespace pagecache::scenario
