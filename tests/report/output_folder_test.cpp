// OutputFolder's commit on the paths the command-line tests cannot steer: a filesystem without
// RENAME_EXCHANGE, a folder that changes between the check and the swap, a run that fails.
#include "report/output_folder.hpp"
#include "report/output_rules.hpp"

#include "support/files.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace fs = std::filesystem;
using pagecache::report::OutputFolder;
using pagecache::testing::names;
using pagecache::testing::scratch;
using pagecache::testing::slurp;

namespace {

// A committed output folder at `dir` whose summary.json holds `text`.
void make_outputs(const fs::path& dir, const std::string& text, OutputFolder::Swap swap = OutputFolder::Swap::Exchange) {
  OutputFolder folder(dir.string());
  std::ofstream(folder.staging() / "summary.json") << text;
  CHECK(folder.commit(swap).empty());
}

}  // namespace

TEST_CASE("without RENAME_EXCHANGE, a folder of pcsim's is replaced by renaming it aside and the new one in", "[report][out]") {
  const fs::path dir = scratch("aside");
  make_outputs(dir / "out", "first");
  make_outputs(dir / "out", "second", OutputFolder::Swap::AsideThenIn);
  CHECK(slurp(dir / "out" / "summary.json") == "second");
  CHECK(names(dir / "out") == std::set<std::string>{".pcsim-output", "summary.json"});
  CHECK(names(dir) == std::set<std::string>{"out"});
}

TEST_CASE("a folder that gains a foreign file after the check is refused when committing, and the staging folder goes", "[report][out]") {
  const fs::path dir = scratch("late");
  make_outputs(dir / "out", "first");
  {
    OutputFolder folder((dir / "out").string());
    std::ofstream(folder.staging() / "summary.json") << "second";
    std::ofstream(dir / "out" / "notes.txt") << "mine";
    CHECK_THROWS_AS(folder.commit(), pagecache::ConfigError);
  }
  CHECK(slurp(dir / "out" / "summary.json") == "first");
  CHECK(slurp(dir / "out" / "notes.txt") == "mine");
  CHECK(names(dir) == std::set<std::string>{"out"});
}

TEST_CASE("an output folder that is never committed leaves nothing behind", "[report][out]") {
  const fs::path dir = scratch("uncommitted");
  {
    OutputFolder folder((dir / "out").string());
    CHECK(fs::exists(folder.staging() / ".pcsim-output"));
    std::ofstream(folder.staging() / "timeline.csv") << "half a file";
  }
  CHECK(fs::is_empty(dir));
}

TEST_CASE("a replaced folder is deleted if it is pcsim's, and kept whole under a visible name if someone wrote into it", "[report][out]") {
  const fs::path dir = scratch("replaced");
  fs::create_directories(dir / ".old");
  std::ofstream(dir / ".old" / ".pcsim-output") << pagecache::report::kMarkerText;
  std::ofstream(dir / ".old" / "timeline.csv") << "rows";
  CHECK_FALSE(pagecache::report::remove_replaced(dir / ".old", dir / "out"));
  CHECK(fs::is_empty(dir));

  fs::create_directories(dir / ".old");
  std::ofstream(dir / ".old" / ".pcsim-output") << pagecache::report::kMarkerText;
  std::ofstream(dir / ".old" / "timeline.csv") << "rows";
  std::ofstream(dir / ".old" / "notes.txt") << "mine";
  const auto warning = pagecache::report::remove_replaced(dir / ".old", dir / "out");
  REQUIRE(warning);
  const std::set<std::string> left = names(dir);
  REQUIRE(left.size() == 1);
  const fs::path kept = dir / *left.begin() / "out";
  CHECK(left.begin()->rfind("out.kept-", 0) == 0);
  CHECK_THAT(*warning, Catch::Contains("holds 'notes.txt'") && Catch::Contains(kept.string()));
  CHECK(names(kept) == std::set<std::string>{".pcsim-output", "notes.txt", "timeline.csv"});
  CHECK(slurp(kept / "notes.txt") == "mine");
}
