// A task's [[...tasks.access]] tables: its reads over file sets, in epochs.

#include "scenario/loader_sections.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::scenario {

namespace {

AccessSpec read_access(TomlReader& a, const std::vector<FileSetSpec>& sets) {
  AccessSpec spec;
  spec.file_set = a.required_name("files");
  const auto set = std::find_if(sets.begin(), sets.end(), [&](const FileSetSpec& x) { return x.name == spec.file_set; });
  if (set == sets.end()) {
    a.fail("files", fmt::format("no file set named '{}' (a [[file_sets]] table; a file is read with read = [...])", spec.file_set));
  }
  const std::string pattern = a.string("pattern", "sequential");
  if (pattern == "random") {
    spec.pattern = AccessPattern::Random;
  } else if (pattern != "sequential") {
    a.fail("pattern", fmt::format("'{}': expected \"sequential\" or \"random\"", pattern));
  }
  const std::int64_t seed = a.optional_integer("seed").value_or(0);
  if (seed < 0) a.fail("seed", fmt::format("must be >= 0, got {}", seed));
  spec.seed = static_cast<std::uint64_t>(seed);
  spec.replacement = a.optional_bool("replacement").value_or(false);
  if (spec.replacement && spec.pattern != AccessPattern::Random) {
    a.fail("replacement", "draws with replacement need pattern = \"random\" (sequential reads each file once, in order)");
  }
  spec.count = a.optional_integer("count").value_or(set->count);
  if (spec.count < 1) a.fail("count", fmt::format("must be >= 1, got {}", spec.count));
  if (!spec.replacement && spec.count > set->count) {
    a.fail("count", fmt::format("{} files per epoch, more than the {} of set '{}': without replacement each is read at most once per epoch",
                                spec.count, set->count, set->name));
  }
  // A large repeat or count (with replacement) is refused with the run's estimate (check_limits).
  spec.repeat = a.optional_integer("repeat").value_or(1);
  if (spec.repeat < 1) a.fail("repeat", fmt::format("must be >= 1 (epochs), got {}", spec.repeat));
  a.finish();
  return spec;
}

}  // namespace

std::vector<AccessSpec> read_accesses(TomlReader& task, const std::vector<FileSetSpec>& sets) {
  std::vector<AccessSpec> accesses;
  const auto tables = task.tables("access");
  accesses.reserve(tables.size());
  for (std::size_t i = 0; i < tables.size(); ++i) {
    TomlReader a(*tables[i], task.child_path("access", i), task.file());
    accesses.push_back(read_access(a, sets));
  }
  return accesses;
}

}  // namespace pagecache::scenario
