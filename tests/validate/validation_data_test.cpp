// The readers of the validation data and of kept measurements, without running pcsim: the CSV
// rules (header, fields, numbers), each file's checks, the kept folder's checks across its
// files, the report's refusal of NaN and infinity, --switch's parsing, and the fuzzer's
// contract on its seeds (fuzz/seeds/validation-*).
#include "validate/csv.hpp"
#include "validate/here.hpp"
#include "validate/here_data.hpp"
#include "validate/paper_data.hpp"
#include "validate/switches.hpp"
#include "validate/validation.hpp"

#include "validation_property.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace pagecache;
using namespace pagecache::validate;

namespace {

// `text` as a table needing `columns`: "" if it reads, else the message.
std::string refusal(const std::string& text, const std::vector<std::string>& columns) {
  try {
    CsvTable(text, "t.csv", columns);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return {};
}

// The message of reading `field` of a one-row table as `read` does, or "" if it reads.
template <class Read>
std::string field_refusal(const std::string& field, const Read& read) {
  const CsvTable t("x,y\n" + field + ",0\n", "t.csv", {"x"});  // y: so that an empty x is a row
  try {
    read(t.row(0));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("a validation CSV needs its header, its columns once each and every row as long as the header", "[validate][data]") {
  struct Case {
    std::string text;
    std::string said;  // "" : reads
  };
  const std::vector<Case> cases = {
      {"", "t.csv:1: the file is empty; expected a header line naming the columns a,b"},
      {"\n1,2\n", "t.csv:1: no header line"},
      {"\r\n", "t.csv:1: no header line"},
      {"a\n1\n", "t.csv:1: no column 'b' in the header 'a' (expected the columns a,b)"},
      {"1,2\n3,4\n", "t.csv:1: no column 'a'"},
      {"a,b,a\n", "t.csv:1: column 'a' twice in the header"},
      {"a,b\n1,2\n3\n", "t.csv:3: 1 fields, expected 2 as in the header"},
      {"a,b\n1,2,3\n", "t.csv:2: 3 fields, expected 2 as in the header"},
      {"a,b\n1,2", ""},                               // no line end at the end
      {"\xEF\xBB\xBF" "a,b\r\n1,2\r\n\r\n3,4\r\n", ""},  // a byte order mark, CRLF, a blank line
      {"b,x,a\n1,,2\n", ""},                          // other columns, in any order
  };
  for (const Case& c : cases) {
    INFO(c.text);
    const std::string said = refusal(c.text, {"a", "b"});
    if (c.said.empty()) {
      CHECK(said.empty());
    } else {
      CHECK_THAT(said, Catch::StartsWith(c.said));
    }
  }
  const CsvTable t("\xEF\xBB\xBF" "a,b\r\n1,\r\n\r\n3,4", "t.csv", {"a", "b"});
  REQUIRE(t.size() == 2);
  CHECK(t.row(0).line() == 2);
  CHECK(t.row(1).line() == 4);  // blank lines count
  CHECK(t.row(1).text("b") == "4");
  CHECK_THROWS_WITH(t.row(0).text("b"), "t.csv:2: column 'b': empty");
  CHECK_THROWS_AS(t.row(0).text("c"), InvariantError);  // not asked for: pcsim's bug, not the file's
  // Optional columns: read when there.
  const CsvTable older("a,b\n1,2\n", "t.csv", {"a"}, {"b", "c"});
  CHECK(older.has("b"));
  CHECK_FALSE(older.has("c"));
}

TEST_CASE("a validation CSV's numbers are finite, of the sign asked for, and nothing but the number", "[validate][data]") {
  struct Case {
    std::string field;
    Sign sign;
    std::string said;  // "" : reads
  };
  const std::vector<Case> cases = {
      {"1.5", Sign::Any, ""},
      {"-0.397", Sign::Any, ""},
      {"1e3", Sign::Positive, ""},
      {"0", Sign::NotNegative, ""},
      {"1e-400", Sign::NotNegative, ""},  // underflows to 0: finite
      {"", Sign::Any, "t.csv:2: column 'x': empty, expected a number"},
      {"abc", Sign::Any, "t.csv:2: column 'x': 'abc' is not a number"},
      {" 1", Sign::Any, "' 1' is not a number"},
      {"1 ", Sign::Any, "'1 ' is not a number"},
      {"1.5s", Sign::Any, "'1.5s' is not a number"},
      {"NaN", Sign::Any, "'NaN' is not a number"},
      {"-nan", Sign::Any, "'-nan' is not a number"},
      {"nan(0x1)", Sign::Any, "'nan(0x1)' is not a number"},
      {"inf", Sign::Any, "'inf' is not a finite number"},
      {"-Infinity", Sign::Any, "'-Infinity' is not a finite number"},
      {"1e400", Sign::Any, "'1e400' is not a finite number"},
      {"-1", Sign::NotNegative, "'-1' is negative"},
      {"0", Sign::Positive, "'0' is not above 0"},
      {"-0", Sign::Positive, "'-0' is not above 0"},
      {"1\x1b[2J", Sign::Any, "'1\\u001b[2J' is not a number"},  // shown harmless on a terminal
  };
  for (const Case& c : cases) {
    INFO(c.field);
    const std::string said = field_refusal(c.field, [&](const CsvTable::Row& r) { return r.number("x", c.sign); });
    if (c.said.empty()) {
      CHECK(said.empty());
    } else {
      CHECK_THAT(said, Catch::Contains(c.said));
    }
  }
  CHECK(CsvTable("x\n0.1\n", "t.csv", {"x"}).row(0).number("x") == std::stod("0.1"));  // as std::stod read the data before
  const auto whole = [](const std::string& field) {
    return field_refusal(field, [](const CsvTable::Row& r) { return r.whole("x", 0, 100); });
  };
  CHECK(whole("42").empty());
  CHECK_THAT(whole("1.0"), Catch::Contains("'1.0' is not a whole number"));
  CHECK_THAT(whole("+1"), Catch::Contains("'+1' is not a whole number"));
  CHECK_THAT(whole("99999999999999999999"), Catch::Contains("is not a whole number"));
  CHECK_THAT(whole("-1"), Catch::Contains("'-1' is negative"));
  CHECK_THAT(whole("101"), Catch::Contains("'101' is above 100"));
  CHECK_THAT(field_refusal("reed", [](const CsvTable::Row& r) { return r.one_of("x", {"read", "write"}); }),
             Catch::Contains("column 'x': 'reed', expected one of read, write"));
}

TEST_CASE("the paper's data files: real durations above 0, phases once, reads and writes together", "[validate][data]") {
  const std::string exp1 = "file_size_gb,task,phase,start_s,end_s,duration_s\n";
  CHECK(read_exp1_phase_times(exp1 + "20,1,read,0,39,39\n20,1,compute,39,39,0\n", "e.csv", true).rows.size() == 2);
  CHECK_THROWS_WITH(read_exp1_phase_times(exp1 + "20,1,read,0,0,0\n", "e.csv", true), Catch::Contains("e.csv:2: column 'duration_s': '0' is not above 0"));
  CHECK(read_exp1_phase_times(exp1 + "20,1,read,0,0,0\n", "w.csv", false).rows.size() == 1);  // WRENCH-cache's may be 0
  CHECK_THROWS_WITH(read_exp1_phase_times(exp1 + "20,1,read,0,2e9,2e9\n", "w.csv", false),
                    Catch::Contains("w.csv:2: column 'end_s': 2000000000 s is beyond 10^9 s"));
  CHECK_THROWS_WITH(read_exp1_phase_times(exp1 + "0,1,read,0,1,1\n", "e.csv", true), Catch::Contains("e.csv:2: column 'file_size_gb': '0' is below 1"));

  const std::string exp2 = "repetition,n_pipelines,pipeline,task,phase,duration_s\n";
  CHECK_THROWS_WITH(read_concurrent_phase_times(exp2 + "1,2,3,1,read,5\n", "c.csv", true), Catch::Contains("c.csv:2: column 'pipeline': '3' is above 2"));
  CHECK_THROWS_WITH(read_concurrent_phase_times(exp2 + "1,1,1,1,read,5\n1,1,1,1,read,6\n", "c.csv", true),
                    Catch::Contains("c.csv:3: repetition 1, n_pipelines 1, pipeline 1, task 1, phase read twice (also line 2)"));
  CHECK_THROWS_WITH(read_concurrent_phase_times(exp2 + "1,1,1,1,write,5\n", "c.csv", true),
                    Catch::Contains("c.csv:2: n_pipelines 1, repetition 1: write rows but no read row"));
  CHECK_THROWS_WITH(read_concurrent_phase_times(exp2 + "1,1,1,1,compute,5\n", "c.csv", true),
                    Catch::Contains("c.csv:2: n_pipelines 1, repetition 1: no read or write row"));
  const std::string wrench = "n_pipelines,pipeline,task,phase,start_s,end_s,duration_s\n";
  CHECK(read_concurrent_phase_times(wrench + "1,1,1,read,0,1,1\n1,1,1,write,1,1,0\n", "w.csv", false).rows.size() == 2);

  const std::string memory = "file_size_gb,time_s,total_mb,cached_mb,dirty_mb,shmem_mb\n";
  CHECK(read_exp1_memory_profile(memory + "20,-0.4,1,2,0,1\n", "m.csv").rows.front().time_s == -0.4);  // sampled before the first read
  CHECK_THROWS_WITH(read_exp1_memory_profile(memory + "20,0,1,2e15,0,1\n", "m.csv"), Catch::Contains("m.csv:2: column 'cached_mb':") &&
                                                                                         Catch::Contains("beyond 1 EiB"));
  const std::string cache = "file_size_gb,after_task,after_phase,file,cached_gb\n";
  CHECK_THROWS_WITH(read_exp1_cache_contents(cache + "20,first,read,file_1,1\n", "k.csv"),
                    Catch::Contains("k.csv:2: column 'after_task': 'first' is not a whole number"));
  CHECK_THROWS_WITH(read_exp1_cache_contents(cache + "20,1,read,,1\n", "k.csv"), Catch::Contains("k.csv:2: column 'file': empty"));
}

namespace {

// A kept folder of one case of one pipeline and one task, two repetitions.
KeptTexts kept() {
  KeptTexts t;
  t.runs = "case,pipelines,tasks,file_size,compute_s,chunk,repetition,makespan_s,memory_total,in_use_at_start,free_at_start,dropped_all_caches\n"
           "c,1,1,100000000,0.5,50000000,1,2.0,16000000000,0,15000000000,1\n"
           "c,1,1,100000000,0.5,50000000,2,2.1,16000000000,0,15000000000,1\n";
  t.phases = "case,repetition,pipeline,task,phase,start_s,end_s\n"
             "c,1,1,1,read,0,0.5\nc,1,1,1,compute,0.5,1.0\nc,1,1,1,write,1.0,2.0\n"
             "c,2,1,1,read,0,0.6\nc,2,1,1,compute,0.6,1.1\nc,2,1,1,write,1.1,2.1\n";
  t.memory = "case,repetition,time_s,free,cached,dirty,writeback\nc,1,0,15000000000,0,0,0\nc,2,0,15000000000,0,0,0\nc,2,1.5,14000000000,1,2,3\n";
  return t;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("kept measurements are checked across their files: each run whole, each phase once, samples in time order", "[validate][data][here]") {
  const HereMeasurements m = parse_here(kept());
  REQUIRE(m.runs.size() == 2);
  CHECK(m.runs[1].phases.size() == 3);
  CHECK(m.runs[1].memory.size() == 2);
  CHECK(m.runs[0].others_busy_cores == -1.0);  // an older folder: not recorded

  struct Case {
    std::string what;
    KeptTexts texts;
    std::string said;
  };
  const KeptTexts k = kept();
  auto with_runs = [&](std::string runs) { KeptTexts t = k; t.runs = std::move(runs); return t; };
  auto with_phases = [&](std::string phases) { KeptTexts t = k; t.phases = std::move(phases); return t; };
  auto with_memory = [&](std::string memory) { KeptTexts t = k; t.memory = std::move(memory); return t; };
  const std::vector<Case> cases = {
      {"a repetition twice", with_runs(replaced(k.runs, "50000000,2,", "50000000,1,")), "runs.csv:3: case c repetition 1 twice (also line 2)"},
      {"repetitions of other sizes", with_runs(replaced(k.runs, "0.5,50000000,2", "0.5,25000000,2")),
       "runs.csv:3: case c has other pipelines, tasks, file size, compute time or chunk than on line 2"},
      {"too many tasks", with_runs(replaced(k.runs, "c,1,1,100000000,0.5,50000000,1", "c,1000,1001,100000000,0.5,50000000,1")),
       "runs.csv:2: column 'tasks': 1000 pipelines of 1001 tasks are more than the 1000000 tasks pcsim simulates"},
      {"an activity figure below -1", with_runs(k.runs.substr(0, k.runs.find('\n')) + ",others_busy_cores,steal_pct,reported_bytes\n" +
                                                "c,1,1,100000000,0.5,50000000,1,2.0,16000000000,0,15000000000,1,-2,0,0\n"),
       "runs.csv:2: column 'others_busy_cores': -2 is neither -1 (not measured) nor from 0 to"},
      {"a compute phase missing", with_phases(replaced(k.phases, "c,2,1,1,compute,0.6,1.1\n", "")),
       "runs.csv:3: case c repetition 2: no compute phase of pipeline 1, task 1 in phases.csv"},
      {"a pipeline beyond the case's", with_phases(replaced(k.phases, "c,2,1,1,read", "c,2,2,1,read")),
       "phases.csv:5: column 'pipeline': 2 is beyond case c's 1 pipelines (runs.csv:3)"},
      {"a sample before the one above it", with_memory(replaced(k.memory, "c,2,1.5,", "c,2,0.0,") + "c,2,0.5,1,1,1,1\nc,2,0.2,1,1,1,1\n"),
       "memory.csv:6: column 'time_s': 0.2 is before the sample of line 5 of the same run"},
      {"a sample of no run", with_memory(k.memory + "d,1,0,1,1,1,1\n"), "memory.csv:5: case d repetition 1 is not in runs.csv"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    CHECK_THROWS_WITH(parse_here(c.texts), Catch::Contains(c.said));
  }
}

TEST_CASE("validate --here's score refuses a real figure so short that the error against it overflows", "[validate][data][here]") {
  KeptTexts t = kept();
  t.platform_toml = R"(
[[hosts]]
name = "m"
memory = "16 GB"
memory_read_bw = "4 GB/s"
memory_write_bw = "2 GB/s"
[[hosts.disks]]
name = "disk"
read_bw = "500 MB/s"
write_bw = "250 MB/s"
)";
  CHECK_NOTHROW(score_here(parse_here(t)));
  t.phases = replaced(replaced(t.phases, "c,1,1,1,read,0,0.5", "c,1,1,1,read,0,1e-310"), "c,2,1,1,read,0,0.6", "c,2,1,1,read,0,1e-310");
  CHECK_THROWS_WITH(score_here(parse_here(t)), Catch::Contains("phases.csv: case c: the real read of task 1, 1e-310 s, is too short to compare with"));
}

TEST_CASE("validate's report refuses to write NaN or infinity into JSON or HTML", "[validate][data][json]") {
  Report report;
  report.profile = "linux";
  CaseResult c;
  c.name = "exp2_local";
  c.figures = {{"n=1 read", 5.0, 6.0, 7.0}};
  c.mean_error_pct = 20.0;
  report.cases = {c};
  CHECK_NOTHROW(report.json());
  CHECK_NOTHROW(report.html());
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Report broken = report;
    broken.cases[0].mean_error_pct = bad;
    CHECK_THROWS_AS(broken.json(), InvariantError);
    CHECK_THROWS_WITH(broken.html(), Catch::Contains("validate: case exp2_local: mean_error_pct is"));
    broken = report;
    broken.cases[0].figures[0].real = 0.0;  // an error relative to 0
    CHECK_THROWS_WITH(broken.json(), Catch::Contains("n=1 read error is inf"));
    broken = report;
    broken.cases[0].extra = {{"max_dirty_diff_pct_of_memory", bad}};
    CHECK_THROWS_AS(check_finite(broken), InvariantError);
  }
}

TEST_CASE("validate --switch takes NAME=true or NAME=false and says so otherwise", "[validate][data]") {
  const auto parsed = parse_switches({"background_writeback=false", "dirty_throttling=true"});
  REQUIRE(parsed.size() == 2);
  CHECK(parsed[0] == std::pair<std::string, bool>{"background_writeback", false});
  CHECK(parsed[1] == std::pair<std::string, bool>{"dirty_throttling", true});
  for (const char* bad : {"background_writeback", "background_writeback=", "background_writeback=no", "=false", "a=TRUE"}) {
    INFO(bad);
    CHECK_THROWS_WITH(parse_switches({bad}), Catch::StartsWith(std::string("--switch '") + bad + "': expected --switch NAME=true|false"));
  }
}

TEST_CASE("the validation fuzzer's seeds and finds keep its contract: read, or refused naming file and line", "[validate][data][fuzz]") {
  std::vector<std::filesystem::path> seeds;
  for (const char* dir : {PAGECACHE_FUZZ_SEEDS_DIR, PAGECACHE_FUZZ_REGRESSIONS_DIR}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().filename().string().rfind("validation-", 0) == 0) seeds.push_back(entry.path());
    }
  }
  std::sort(seeds.begin(), seeds.end());
  REQUIRE(seeds.size() >= 10);
  for (const auto& seed : seeds) {
    std::ifstream in(seed, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    INFO(seed.filename().string());
    CHECK(fuzz::check_validation_text(text.str()).empty());
  }
  // The contract itself catches a reader's promise broken and a message without its line.
  CHECK_FALSE(fuzz::check_phase_times({"e.csv", {{2, 20, 1, "read", 1.0, std::nan("")}}}, true).empty());
  CHECK(fuzz::check_kept_folder("runs", "phases", "memory").empty());  // refused at runs.csv:1
  CHECK(fuzz::check_kept_folder(kept().runs, kept().phases, kept().memory).empty());
  CHECK_FALSE(fuzz::unlocated("runs.csv: no runs", "runs.csv").empty());
  CHECK(fuzz::unlocated("runs.csv:1: no runs after the header", "runs.csv").empty());
}
