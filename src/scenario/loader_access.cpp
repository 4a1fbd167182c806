// A task's [[...tasks.access]] tables: its reads over file sets, in epochs; or its reads and
// writes of parts of one file, by pattern, in epochs.

#include "scenario/loader_sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace pagecache::scenario {

namespace {

// The keys of an access of one file, each refused on an access of a file set.
constexpr const char* kFileKeys[] = {"request", "offset", "length", "stride", "ranges", "mode", "advice", "reshuffle", "invalidate", "drop_after", "runtime"};

AccessSpec read_set_access(TomlReader& a, const std::vector<FileSetSpec>& sets) {
  AccessSpec spec;
  spec.file_set = a.required_name("files");
  const auto set = std::find_if(sets.begin(), sets.end(), [&](const FileSetSpec& x) { return x.name == spec.file_set; });
  if (set == sets.end()) {
    a.fail("files", fmt::format("no file set named '{}' (a [[file_sets]] table; one file is accessed with file = \"NAME\")", spec.file_set));
  }
  for (const char* key : kFileKeys) {
    if (a.has(key)) a.fail(key, "a key of an access of one file (file = \"NAME\"), not of a file set's");
  }
  const std::string pattern = a.string("pattern", "sequential");
  if (pattern == "random") {
    spec.pattern = AccessPattern::Random;
  } else if (pattern != "sequential") {
    a.fail("pattern", fmt::format("'{}': expected \"sequential\" or \"random\" (strided and ranges are patterns of one file's parts)", pattern));
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

// One value of a size list: "4 KiB" or a number of bytes.
std::int64_t size_value(const TomlReader& a, const toml::node& node, const std::string& where) {
  if (const auto bytes = node.value_exact<std::int64_t>()) {
    if (*bytes < 0) a.fail("ranges", fmt::format("{}: must not be negative, got {}", where, *bytes));
    if (*bytes > units::kMaxBytes) a.fail("ranges", fmt::format("{}: {} bytes is too large (at most 1 EiB)", where, *bytes));
    return *bytes;
  }
  if (const auto text = node.value_exact<std::string>()) {
    try {
      return units::parse_size(*text);
    } catch (const ConfigError& e) {
      a.fail("ranges", fmt::format("{}: {}", where, e.what()));
    }
  }
  a.fail("ranges", fmt::format("{}: expected a size such as \"4 KiB\" or a number of bytes", where));
}

// ranges = [[offset, length], ...], each within the file.
std::vector<std::pair<std::int64_t, std::int64_t>> read_ranges(TomlReader& a, const FileSpec& file) {
  const toml::node* node = a.raw("ranges");
  if (node == nullptr) a.fail_table("pattern = \"ranges\" needs ranges = [[offset, length], ...] (missing key 'ranges')");
  const toml::array* list = node->as_array();
  if (list == nullptr || list->empty()) a.fail("ranges", "expected a list of [offset, length] pairs, at least one");
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;
  ranges.reserve(list->size());
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string where = fmt::format("ranges[{}]", i);
    const toml::array* pair = list->get(i)->as_array();
    if (pair == nullptr || pair->size() != 2) a.fail("ranges", fmt::format("{}: expected [offset, length]", where));
    const std::int64_t offset = size_value(a, *pair->get(0), where);
    const std::int64_t length = size_value(a, *pair->get(1), where);
    if (length <= 0) a.fail("ranges", fmt::format("{}: the length is {}: a range is at least one byte", where, length));
    if (offset > file.size - length) {
      a.fail("ranges", fmt::format("{}: {} bytes at {} are not within file '{}' ({} bytes)", where, length, offset, file.name, file.size));
    }
    ranges.emplace_back(offset, length);
  }
  return ranges;
}

template <typename T, std::size_t N>
T choice(TomlReader& a, const char* key, const char* const (&names)[N], T fallback) {
  const auto text = a.optional_string(key);
  if (!text) return fallback;
  for (std::size_t i = 0; i < N; ++i) {
    if (*text == names[i]) return static_cast<T>(i);
  }
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) expected += fmt::format("{}\"{}\"", i == 0 ? "" : i + 1 == N ? " or " : ", ", names[i]);
  a.fail(key, fmt::format("'{}': expected {}", *text, expected));
}

// The region's keys (offset, length, stride, count) of a pattern that has a region.
void read_region(TomlReader& a, const FileSpec& file, AccessSpec& spec) {
  spec.offset = a.optional_size("offset").value_or(0);
  if (spec.offset >= file.size) a.fail("offset", fmt::format("{} is not within file '{}' ({} bytes)", spec.offset, file.name, file.size));
  spec.length = a.optional_size("length").value_or(file.size - spec.offset);
  if (spec.length <= 0) a.fail("length", fmt::format("must be > 0, got {}", spec.length));
  if (spec.length > file.size - spec.offset) {
    a.fail("length", fmt::format("{} bytes from offset {} end past the end of file '{}' ({} bytes)", spec.length, spec.offset, file.name, file.size));
  }
  const bool strided = spec.pattern == AccessPattern::Strided;
  if (strided) {
    spec.stride = a.optional_size("stride").value_or(0);
    if (!a.has("stride")) a.fail_table("pattern = \"strided\" needs stride (bytes from one request's start to the next's; missing key 'stride')");
    if (spec.stride < spec.request) a.fail("stride", fmt::format("{} bytes, shorter than a request ({} bytes)", spec.stride, spec.request));
    if (spec.length < spec.request) {
      a.fail("length", fmt::format("{} bytes, shorter than a request ({} bytes): no request fits", spec.length, spec.request));
    }
  } else if (a.has("stride")) {
    a.fail("stride", "a key of pattern = \"strided\"");
  }
  // What fits: each part of the region once, or each stride's request.
  const std::int64_t fit = strided ? (spec.length - spec.request) / spec.stride + 1 : (spec.length + spec.request - 1) / spec.request;
  if (spec.pattern == AccessPattern::Random && fit > std::numeric_limits<std::uint32_t>::max()) {
    a.fail(a.has("request") ? "request" : "length",
           fmt::format("{} requests of {} bytes to draw from, more than the 2^32 - 1 a random pattern may have: larger requests make fewer", fit,
                       spec.request));
  }
  spec.count = a.optional_integer("count").value_or(fit);
  if (spec.count < 1) a.fail("count", fmt::format("must be >= 1, got {}", spec.count));
  const bool bounded = strided || spec.mode == AccessMode::Append || (spec.pattern == AccessPattern::Random && !spec.replacement);
  if (bounded && spec.count > fit) {
    a.fail("count", fmt::format("{} requests per epoch, more than the {} that fit the region ({}: each at most once per epoch)", spec.count, fit,
                                strided ? "strided" : spec.mode == AccessMode::Append ? "an append" : "random without replacement"));
  }
}

AccessSpec read_file_access(TomlReader& a, AccessTargets& targets, std::int64_t chunk_size) {
  static constexpr const char* kPatterns[] = {"sequential", "random", "strided", "ranges"};
  static constexpr const char* kModes[] = {"read", "write", "append"};
  static constexpr const char* kAdvice[] = {"normal", "sequential", "random"};
  AccessSpec spec;
  spec.file = a.required_name("file");
  const FileSpec* const found = targets.file(spec.file);
  if (found == nullptr) {
    a.fail("file", fmt::format("no file named '{}' (a [[files]] table; a file set is read with files = \"SET\")", spec.file));
  }
  const FileSpec& file = *found;
  spec.pattern = choice(a, "pattern", kPatterns, AccessPattern::Sequential);
  spec.mode = choice(a, "mode", kModes, AccessMode::Read);
  if (spec.mode == AccessMode::Append && spec.pattern != AccessPattern::Sequential) {
    a.fail("pattern", "an append writes in order from offset to the file's end: pattern = \"sequential\"");
  }
  spec.advice = choice(a, "advice", kAdvice, AccessAdvice::Normal);
  if (a.has("advice") && spec.mode != AccessMode::Read) a.fail("advice", "posix_fadvise advice is for reads (mode = \"read\")");
  const bool random = spec.pattern == AccessPattern::Random;
  for (const char* key : {"seed", "replacement", "reshuffle"}) {
    if (a.has(key) && !random) a.fail(key, "a key of pattern = \"random\"");
  }
  spec.reshuffle = a.optional_bool("reshuffle").value_or(true);
  spec.invalidate = a.optional_bool("invalidate").value_or(false);
  spec.drop_after = a.optional_bool("drop_after").value_or(false);
  spec.runtime = a.optional_duration("runtime").value_or(0.0);
  if (spec.runtime < 0.0) a.fail("runtime", fmt::format("must be >= 0 seconds (0: no limit), got {}", spec.runtime));
  const std::int64_t seed = a.optional_integer("seed").value_or(0);
  if (seed < 0) a.fail("seed", fmt::format("must be >= 0, got {}", seed));
  spec.seed = static_cast<std::uint64_t>(seed);
  spec.replacement = a.optional_bool("replacement").value_or(false);
  spec.request = a.optional_size("request").value_or(chunk_size);
  if (spec.request <= 0) a.fail("request", fmt::format("must be > 0 bytes, got {}", spec.request));
  if (spec.pattern == AccessPattern::Ranges) {
    for (const char* key : {"offset", "length", "stride", "count"}) {
      if (a.has(key)) a.fail(key, "not a key of pattern = \"ranges\" (each range is [offset, length], read once per epoch)");
    }
    spec.ranges = read_ranges(a, file);
  } else {
    if (a.has("ranges")) a.fail("ranges", "a key of pattern = \"ranges\"");
    read_region(a, file, spec);
  }
  // A large repeat or count is refused with the run's estimate (check_limits).
  spec.repeat = a.optional_integer("repeat").value_or(1);
  if (spec.repeat < 1) a.fail("repeat", fmt::format("must be >= 1 (epochs), got {}", spec.repeat));
  a.finish();
  return spec;
}

}  // namespace

const FileSpec* AccessTargets::file(const std::string& name) {
  if (index_.empty()) {
    index_.reserve(files_.size());
    for (const FileSpec& f : files_) index_.emplace(f.name, &f);
  }
  const auto it = index_.find(name);
  return it == index_.end() ? nullptr : it->second;
}

std::vector<AccessSpec> read_accesses(TomlReader& task, AccessTargets& targets, std::int64_t chunk_size) {
  std::vector<AccessSpec> accesses;
  const auto tables = task.tables("access");
  accesses.reserve(tables.size());
  for (std::size_t i = 0; i < tables.size(); ++i) {
    TomlReader a(*tables[i], task.child_path("access", i), task.file());
    if (a.has("file") && a.has("files")) a.fail("file", "an access reads a file set (files = \"SET\") or one file (file = \"NAME\"), not both");
    if (!a.has("file") && !a.has("files")) {
      a.fail_table("an access needs files = \"SET\" (a file set) or file = \"NAME\" (parts of one file)");
    }
    accesses.push_back(a.has("file") ? read_file_access(a, targets, chunk_size) : read_set_access(a, targets.sets()));
  }
  return accesses;
}

}  // namespace pagecache::scenario
