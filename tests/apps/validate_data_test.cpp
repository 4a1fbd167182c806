// pcsim validate's inputs read as strictly as a scenario, run as a user runs it: a copy of the
// validation data (validation/paper/) or of kept measurements (validation/here/) with one file
// broken is refused with exit 2, a message naming the file, the line and the column, and
// nothing written. And every JSON file pcsim writes is strict JSON (no NaN or infinity), also
// after inputs at the edge of what is accepted.
#include "support/files.hpp"
#include "support/pcsim_cli.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pagecache::testing::kPlatform;
using pagecache::testing::kWorkload;
using pagecache::testing::Outcome;
using pagecache::testing::pcsim;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

using Edit = std::function<std::string(const std::string&)>;

// One file of a data folder changed: its text through `edit`, or the file removed.
struct Broken {
  std::string what;
  std::string file;
  Edit edit;  // empty: the file is removed
  std::vector<std::string> said;  // the message holds each
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// The edits, by line number from 1 as the messages count them; a line's '\r' is kept.
Edit empty() {
  return [](const std::string&) { return std::string(); };
}
Edit header_only() {
  return [](const std::string& t) { return t.substr(0, t.find('\n') + 1); };
}
Edit without_line(int number) {
  return [number](const std::string& t) {
    auto lines = lines_of(t);
    lines.erase(lines.begin() + number - 1);
    return joined(lines);
  };
}
Edit without_lines_starting(const std::string& prefix) {
  return [prefix](const std::string& t) {
    std::vector<std::string> kept;
    for (const std::string& l : lines_of(t))
      if (l.rfind(prefix, 0) != 0) kept.push_back(l);
    return joined(kept);
  };
}
Edit without_lines_matching(const std::string& pattern) {
  return [pattern](const std::string& t) {
    const std::regex re(pattern);
    std::vector<std::string> kept;
    for (const std::string& l : lines_of(t))
      if (!std::regex_search(l, re, std::regex_constants::match_continuous)) kept.push_back(l);
    return joined(kept);
  };
}
Edit line_twice(int number) {
  return [number](const std::string& t) {
    auto lines = lines_of(t);
    lines.insert(lines.begin() + number, lines[number - 1]);
    return joined(lines);
  };
}
// Field `field` (from 0) of line `number` set to `value`.
Edit field(int number, int field, const std::string& value) {
  return [=](const std::string& t) {
    auto lines = lines_of(t);
    std::string& line = lines[number - 1];
    const bool cr = !line.empty() && line.back() == '\r';
    if (cr) line.pop_back();
    std::vector<std::string> fields;
    std::stringstream parts(line);
    for (std::string f; std::getline(parts, f, ',');) fields.push_back(f);
    fields.at(field) = value;
    line.clear();
    for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
    if (cr) line += '\r';
    return joined(lines);
  };
}
Edit without_last_field(int number) {
  return [number](const std::string& t) {
    auto lines = lines_of(t);
    std::string& line = lines[number - 1];
    line = line.substr(0, line.rfind(','));
    return joined(lines);
  };
}

// A copy of `source` in a fresh folder, one file broken as `b` says; the copy's path.
fs::path broken_copy(const fs::path& source, const Broken& b, const fs::path& dir) {
  const fs::path data = dir / "data";
  fs::copy(source, data, fs::copy_options::recursive);
  const fs::path file = data / b.file;
  if (!b.edit) {
    fs::remove(file);
  } else {
    const std::string text = b.edit(slurp(file));
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  }
  return data;
}

// Refused: exit 2, the message, no NaN in it, nothing written.
void check_refused(const Broken& b, const Outcome& o, const fs::path& dir) {
  INFO(b.what << " (" << b.file << "): exit " << o.status << ": " << o.output);
  CHECK(o.status == 2);
  for (const std::string& s : b.said) CHECK_THAT(o.output, Catch::Contains(s));
  CHECK_THAT(o.output, !Catch::Contains("nan") && !Catch::Contains("map::at"));
  CHECK_FALSE(fs::exists(dir / "v.json"));
  CHECK_FALSE(fs::exists(dir / "v.html"));
}

const fs::path kPaper = PAGECACHE_VALIDATION_DIR;
const fs::path kKept = fs::path(PCSIM_SOURCE_DIR) / "validation" / "here" / "dev-vm-2026-12-03-d";

// Numbers a JSON or HTML file must not hold: C's printf spellings of NaN and infinity.
const std::regex kNonFinite("(^|[^A-Za-z_])-?(nan|inf)([^A-Za-z_]|$)", std::regex::icase);

}  // namespace

TEST_CASE("pcsim validate --data: a broken file is refused with exit 2, naming its file, line and column", "[cli][validate][errors]") {
  const std::vector<Broken> cases = {
      // Each quoted in issue 33, and what today's pcsim did.
      {"an empty memory profile (was a segmentation fault)", "exp1_real_memory_profile.csv", empty(),
       {"exp1_real_memory_profile.csv:1: the file is empty"}},
      {"a memory profile of a header alone (was a segmentation fault)", "exp1_real_memory_profile.csv", header_only(),
       {"exp1_real_memory_profile.csv: no row with file_size_gb 20"}},
      {"an empty Exp 1 WRENCH-cache file (was map::at, exit 1)", "exp1_wrench_cache_phase_times.csv", empty(),
       {"exp1_wrench_cache_phase_times.csv:1: the file is empty"}},
      {"an empty Exp 2 WRENCH-cache file (was map::at, exit 1)", "exp2_wrench_cache_phase_times.csv", empty(),
       {"exp2_wrench_cache_phase_times.csv:1: the file is empty"}},
      {"an Exp 3 WRENCH-cache file of a header alone (was map::at, exit 1)", "exp3_wrench_cache_phase_times.csv", header_only(),
       {"exp3_wrench_cache_phase_times.csv: no row with n_pipelines 1"}},
      {"an empty real phase file (was -nan in the JSON, exit 0)", "exp3_real_phase_times.csv", empty(),
       {"exp3_real_phase_times.csv:1: the file is empty"}},
      {"a real phase file of a header alone (was -nan in the JSON, exit 0)", "exp2_real_phase_times.csv", header_only(),
       {"exp2_real_phase_times.csv: no read or write rows"}},
      {"a NaN duration (was nan in the JSON, exit 0)", "exp1_real_phase_times.csv", field(2, 5, "NaN"),
       {"exp1_real_phase_times.csv:2: column 'duration_s': 'NaN' is not a number"}},
      // The classes of fault.
      {"a missing file", "exp1_real_cache_contents.csv", nullptr, {"exp1_real_cache_contents.csv: cannot open the data file: No such file"}},
      {"a missing header", "exp2_real_phase_times.csv", without_line(1), {"exp2_real_phase_times.csv:1: no column 'repetition'"}},
      {"a missing column", "exp3_wrench_cache_phase_times.csv", field(1, 6, "duration"),
       {"exp3_wrench_cache_phase_times.csv:1: no column 'duration_s'"}},
      {"a short row", "exp2_real_phase_times.csv", without_last_field(5), {"exp2_real_phase_times.csv:5: 5 fields, expected 6"}},
      {"an empty field", "exp1_real_cache_contents.csv", field(3, 4, ""), {"exp1_real_cache_contents.csv:3: column 'cached_gb': empty"}},
      {"a word for a number", "exp1_real_memory_profile.csv", field(3, 3, "abc"),
       {"exp1_real_memory_profile.csv:3: column 'cached_mb': 'abc' is not a number"}},
      {"a hexadecimal number, which strtod reads", "exp1_real_memory_profile.csv", field(3, 3, "0x10"),
       {"exp1_real_memory_profile.csv:3: column 'cached_mb': '0x10' is not a number"}},
      {"an infinite duration", "exp3_wrench_cache_phase_times.csv", field(2, 6, "inf"),
       {"exp3_wrench_cache_phase_times.csv:2: column 'duration_s': 'inf' is not a finite number"}},
      {"a duration beyond 10^9 s", "exp1_wrench_cache_phase_times.csv", field(2, 5, "1e12"),
       {"exp1_wrench_cache_phase_times.csv:2: column 'duration_s':", "beyond 10^9 s"}},
      {"a negative amount of memory", "exp1_real_memory_profile.csv", field(4, 4, "-1"),
       {"exp1_real_memory_profile.csv:4: column 'dirty_mb': '-1' is negative"}},
      {"a negative WRENCH-cache duration", "exp1_wrench_cache_phase_times.csv", field(3, 5, "-4"),
       {"exp1_wrench_cache_phase_times.csv:3: column 'duration_s': '-4' is negative"}},
      {"a real read of 0 s, which errors are relative to", "exp2_real_phase_times.csv", field(2, 5, "0"),
       {"exp2_real_phase_times.csv:2: column 'duration_s': '0' is not above 0"}},
      {"a fraction of a pipeline", "exp2_real_phase_times.csv", field(2, 1, "1.5"),
       {"exp2_real_phase_times.csv:2: column 'n_pipelines': '1.5' is not a whole number"}},
      {"an unknown phase", "exp1_real_phase_times.csv", field(2, 2, "reed"),
       {"exp1_real_phase_times.csv:2: column 'phase': 'reed', expected one of read, compute, write"}},
      {"a phase twice", "exp1_real_phase_times.csv", line_twice(2),
       {"exp1_real_phase_times.csv:3: file_size_gb 20, task 1, phase read twice (also line 2)"}},
      {"real reads without writes", "exp3_real_phase_times.csv", without_lines_matching("1,1,[0-9]+,[0-9]+,write"),
       {"exp3_real_phase_times.csv:2: n_pipelines 1, repetition 1: read rows but no write row"}},
      // Rows a case needs.
      {"no rows for the 100 GB run", "exp1_real_phase_times.csv", without_lines_starting("100,"),
       {"exp1_real_phase_times.csv: no row with file_size_gb 100"}},
      {"no row for a phase the simulation has", "exp1_real_phase_times.csv", without_lines_starting("20,3,write"),
       {"exp1_real_phase_times.csv: no row with file_size_gb 20, task 3, phase write"}},
      {"no WRENCH-cache rows for a number of pipelines the real runs have", "exp3_wrench_cache_phase_times.csv", without_lines_starting("8,"),
       {"exp3_wrench_cache_phase_times.csv: no row with n_pipelines 8"}},
      {"no cache contents for the 20 GB run", "exp1_real_cache_contents.csv", without_lines_starting("20,"),
       {"exp1_real_cache_contents.csv: no row with file_size_gb 20"}},
  };
  for (const Broken& b : cases) {
    const fs::path dir = scratch("validate-data");
    const fs::path data = broken_copy(kPaper, b, dir);
    const Outcome o = pcsim(fmt::format("validate --data '{}' --json v.json --report v.html", data.string()), dir);
    check_refused(b, o, dir);
  }
}

TEST_CASE("pcsim validate --from: broken kept measurements are refused with exit 2, naming file, line and column", "[cli][validate][errors]") {
  const std::vector<Broken> cases = {
      {"an empty runs.csv", "runs.csv", empty(), {"runs.csv:1: the file is empty"}},
      {"a runs.csv of a header alone", "runs.csv", header_only(), {"runs.csv:1: no runs after the header"}},
      {"no phases at all", "phases.csv", header_only(),
       {"runs.csv:2: case exp1-8pct repetition 1: no read phase of pipeline 1, task 1 in phases.csv"}},
      {"a run without its memory", "memory.csv", without_lines_starting("exp2-8,3,"),
       {"runs.csv:16: case exp2-8 repetition 3: no memory sample in memory.csv"}},
      {"a missing memory.csv", "memory.csv", nullptr, {"memory.csv: cannot open the data file: No such file"}},
      {"a missing column", "runs.csv", field(1, 7, "makespan"), {"runs.csv:1: no column 'makespan_s'"}},
      {"a short row", "runs.csv", without_last_field(3), {"runs.csv:3: 14 fields, expected 15"}},
      {"a NaN", "memory.csv", field(3, 2, "NaN"), {"memory.csv:3: column 'time_s': 'NaN' is not a number"}},
      {"a NaN for bytes", "memory.csv", field(3, 3, "NaN"), {"memory.csv:3: column 'free': 'NaN' is not a whole number"}},
      {"an infinite time", "memory.csv", field(2, 2, "inf"), {"memory.csv:2: column 'time_s': 'inf' is not a finite number"}},
      {"a negative amount of memory", "memory.csv", field(5, 5, "-3"), {"memory.csv:5: column 'dirty': '-3' is negative"}},
      {"a negative makespan", "runs.csv", field(2, 7, "-5"), {"runs.csv:2: column 'makespan_s': '-5' is not above 0"}},
      {"a word for a pipeline", "phases.csv", field(4, 2, "x"), {"phases.csv:4: column 'pipeline': 'x' is not a whole number"}},
      {"a read that ends before it starts", "phases.csv", field(2, 6, "0.0001"),
       {"phases.csv:2: column 'end_s': '0.0001' is not after start_s '0.000334'"}},
      {"a read of 0 s, which errors are relative to", "phases.csv", field(2, 6, "0.000334"),
       {"phases.csv:2: column 'end_s': '0.000334' is not after start_s '0.000334'"}},
      {"a task beyond the case's", "phases.csv", field(2, 3, "7"), {"phases.csv:2: column 'task': 7 is beyond case exp1-8pct's 3 tasks (runs.csv:2)"}},
      {"a phase twice", "phases.csv", line_twice(2),
       {"phases.csv:3: the read of pipeline 1, task 1 of case exp1-8pct repetition 1 twice (also line 2)"}},
      {"a phase of a run runs.csv lacks", "phases.csv", field(2, 0, "nowhere"), {"phases.csv:2: case nowhere repetition 1 is not in runs.csv"}},
  };
  for (const Broken& b : cases) {
    const fs::path dir = scratch("validate-from");
    const fs::path data = broken_copy(kKept, b, dir);
    const Outcome o = pcsim(fmt::format("validate --from '{}'", data.string()), dir);
    check_refused(b, o, dir);
  }
}

TEST_CASE("validate --switch without '=' or with another value names --switch and what it expects", "[cli][validate][errors]") {
  const fs::path dir = scratch("validate-switch");
  for (const char* given : {"background_writeback", "background_writeback=yes", "=false"}) {
    const Outcome o = pcsim(fmt::format("validate --switch '{}' --report v.html", given), dir);
    INFO(given << ": " << o.output);
    CHECK(o.status == 2);
    CHECK_THAT(o.output, Catch::Contains(fmt::format("--switch '{}': expected --switch NAME=true|false", given)));
    CHECK_THAT(o.output, !Catch::Contains("--set"));
    CHECK_FALSE(fs::exists(dir / "v.html"));
  }
  const Outcome unknown = pcsim("validate --switch no_such_switch=false --report v.html", dir);
  CHECK(unknown.status == 2);
  CHECK_THAT(unknown.output, Catch::Contains("unknown page-cache switch 'no_such_switch'"));
}

namespace {

// `path` parsed by a strict parser (nlohmann::json rejects NaN and Infinity), and no number
// of it NaN or infinite.
void check_strict_json(const fs::path& path) {
  INFO(path.string());
  REQUIRE(fs::exists(path));
  const std::string text = slurp(path);
  nlohmann::json doc;
  REQUIRE_NOTHROW(doc = nlohmann::json::parse(text));
  std::function<void(const nlohmann::json&)> finite = [&](const nlohmann::json& j) {
    if (j.is_number_float()) CHECK(std::isfinite(j.get<double>()));
    if (j.is_structured())
      for (const auto& item : j) finite(item);
  };
  finite(doc);
}

void check_jsonl(const fs::path& path) {
  INFO(path.string());
  int lines = 0;
  for (const std::string& line : lines_of(slurp(path))) {
    if (line.empty()) continue;
    ++lines;
    REQUIRE_NOTHROW(nlohmann::json::parse(line));
  }
  CHECK(lines > 0);
}

}  // namespace

TEST_CASE("every JSON file pcsim writes is strict JSON, without NaN or infinity", "[cli][validate][json]") {
  const fs::path dir = scratch("strict-json");
  SECTION("run: summary.json, timing.json and trace.json, also when every phase takes no time") {
    const std::string empty_files = std::string(kPlatform) +
                                    "[[files]]\nname = \"in\"\nsize = \"0 B\"\n[[files]]\nname = \"out\"\nsize = \"0 B\"\n"
                                    "[[apps]]\nname = \"a\"\n[[apps.tasks]]\nread = \"in\"\nwrite = \"out\"\n";
    for (const auto& [name, text] : {std::pair{"small", std::string(kPlatform) + kWorkload}, std::pair{"zero", empty_files}}) {
      std::ofstream(dir / (std::string(name) + ".toml")) << text;
      const fs::path out = dir / (std::string("out-") + name);
      const Outcome o = pcsim(fmt::format("run {}.toml --out '{}' --trace --quiet", name, out.string()), dir);
      INFO(o.output);
      REQUIRE(o.status == 0);
      for (const char* file : {"summary.json", "timing.json", "trace.json"}) check_strict_json(out / file);
    }
  }
  SECTION("validate --json, with each profile and a switch off") {
    for (const char* options : {"", "--profile paper", "--switch background_writeback=false"}) {
      const Outcome o = pcsim(fmt::format("validate {} --json v.json --report v.html", options), dir);
      INFO(options << ": " << o.output);
      REQUIRE(o.status == 0);
      check_strict_json(dir / "v.json");
      CHECK_FALSE(std::regex_search(slurp(dir / "v.html"), kNonFinite));
    }
  }
  SECTION("sweep run: each results-*.jsonl line and sweep-plan.json") {
    std::ofstream(dir / "two.toml") << fmt::format("scenario = \"{}/scenarios/paper/exp2.toml\"\n[[points]]\n\"pipelines.count\" = 1\n"
                                                   "[[points]]\n\"pipelines.count\" = 2\n",
                                                   PCSIM_SOURCE_DIR);
    const Outcome o = pcsim("sweep run two.toml --out sweep --quiet", dir);
    INFO(o.output);
    REQUIRE(o.status == 0);
    check_strict_json(dir / "sweep" / "sweep-plan.json");
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir / "sweep")) {
      if (entry.path().extension() != ".jsonl") continue;
      ++files;
      check_jsonl(entry.path());
    }
    CHECK(files == 1);
  }
}

TEST_CASE("pcsim validate at the edge of its data: finite errors in strict JSON, or refused naming the file", "[cli][validate][json]") {
  struct Edge {
    Broken change;
    int status;  // 0: accepted, 2: refused
  };
  const std::vector<Edge> edges = {
      {{"a WRENCH-cache phase of 0 s", "exp1_wrench_cache_phase_times.csv", field(2, 5, "0"), {}}, 0},
      {{"WRENCH-cache writes of 0 s", "exp2_wrench_cache_phase_times.csv", field(4, 6, "0"), {}}, 0},
      {{"a real read of 10^-300 s: an error of 10^303 %", "exp1_real_phase_times.csv", field(2, 5, "1e-300"), {}}, 0},
      {{"memory samples of nothing", "exp1_real_memory_profile.csv", field(2, 3, "0"), {}}, 0},
      {{"a real read of 0 s", "exp1_real_phase_times.csv", field(2, 5, "0"), {"exp1_real_phase_times.csv:2: column 'duration_s': '0' is not above 0"}}, 2},
      {{"a real read of 10^-310 s, against which the error overflows", "exp1_real_phase_times.csv", field(2, 5, "1e-310"),
        {"exp1_real_phase_times.csv:2: column 'duration_s': 1e-310 s is too short to compare with"}},
       2},
  };
  for (const Edge& e : edges) {
    const fs::path dir = scratch("validate-edge");
    const fs::path data = broken_copy(kPaper, e.change, dir);
    const Outcome o = pcsim(fmt::format("validate --data '{}' --json v.json --report v.html", data.string()), dir);
    INFO(e.change.what << ": exit " << o.status << ": " << o.output);
    REQUIRE(o.status == e.status);
    if (e.status == 2) {
      check_refused(e.change, o, dir);
      continue;
    }
    check_strict_json(dir / "v.json");
    CHECK_FALSE(std::regex_search(slurp(dir / "v.html"), kNonFinite));
    CHECK_FALSE(std::regex_search(o.output, kNonFinite));
  }
}
