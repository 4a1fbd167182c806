// replace_file, which writes `pcsim validate --json FILE`: whole or not at all, never into a
// folder or through a link.
#include "report/replace_file.hpp"

#include "support/files.hpp"

#include <pagecache/error.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using pagecache::testing::scratch;
using pagecache::testing::slurp;
using pagecache::report::replace_file;


TEST_CASE("replace_file overwrites a file, keeps its permissions, and leaves no temporary file", "[report][json]") {
  const fs::path dir = scratch("json-overwrite");
  std::ofstream(dir / "v.json") << "an older and longer content";
  fs::permissions(dir / "v.json", fs::perms::owner_read | fs::perms::owner_write);
  replace_file((dir / "v.json").string(), "{}\n");
  CHECK(slurp(dir / "v.json") == "{}\n");
  CHECK((fs::status(dir / "v.json").permissions() & fs::perms::all) == (fs::perms::owner_read | fs::perms::owner_write));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("replace_file refuses a folder and leaves what it holds", "[report][json]") {
  const fs::path dir = scratch("json-folder");
  fs::create_directories(dir / "v.json");
  std::ofstream(dir / "v.json" / "keep.txt") << "mine";
  CHECK_THROWS_AS(replace_file((dir / "v.json").string(), "{}\n"), pagecache::ConfigError);
  CHECK(slurp(dir / "v.json" / "keep.txt") == "mine");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("replace_file replaces a symbolic link, not the file it points to", "[report][json]") {
  const fs::path dir = scratch("json-link");
  std::ofstream(dir / "precious.txt") << "mine";
  fs::create_symlink(dir / "precious.txt", dir / "v.json");
  replace_file((dir / "v.json").string(), "{}\n");
  CHECK_FALSE(fs::is_symlink(dir / "v.json"));
  CHECK(slurp(dir / "v.json") == "{}\n");
  CHECK(slurp(dir / "precious.txt") == "mine");
}
