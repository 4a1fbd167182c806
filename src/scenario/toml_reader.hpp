#pragma once
// TomlReader: reads one TOML table of a scenario with the project's units and rules, and
// remembers which keys it read, so that finish() can reject every key it does not know.
// Every error names the file, the line and column (or the option the value came from),
// and the key's full path; an unknown key comes with the known key it most resembles.

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include "formats/common/closest.hpp"
#include "formats/common/names.hpp"

#include <toml++/toml.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::scenario {

/// Where a value came from: "file:line:col", or the option it was given with: "--set KEY=VALUE"
/// for an override, "--files-host H" for an option of load_workflow.
std::string location(const toml::source_region& where, const std::string& file);
/// The same as a ConfigError's InputPlace, with the key's full path: no file or line for a
/// value given by an option.
InputPlace input_place(const toml::source_region& where, const std::string& file, std::string key);

class TomlReader {
 public:
  TomlReader(const toml::table& table, std::string path, const std::string& file)
      : table_(&table), path_(std::move(path)), file_(&file) {}

  const std::string& path() const noexcept { return path_; }
  const std::string& file() const noexcept { return *file_; }
  const toml::table& table() const noexcept { return *table_; }
  bool has(const std::string& key) const { return table_->contains(key); }

  /// "file:line:col: key 'path.key': message", for the key's node (or the table's).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const toml::node* node = table_->get(key);
    const toml::source_region& where = node != nullptr ? node->source() : table_->source();
    throw ConfigError(fmt::format("{}: key '{}': {}", location(where, *file_), full(key), message), input_place(where, *file_, full(key)));
  }
  [[noreturn]] void fail_table(const std::string& message) const {
    throw ConfigError(fmt::format("{}: {}: {}", location(table_->source(), *file_), path_.empty() ? std::string("scenario") : "'" + path_ + "'",
                                  message),
                      input_place(table_->source(), *file_, path_));
  }

  std::optional<std::string> optional_string(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_string()) fail(key, "expected a string");
    return node->value<std::string>();
  }
  std::string string(const std::string& key, const std::string& fallback) { return optional_string(key).value_or(fallback); }
  std::string required_string(const std::string& key) {
    auto v = optional_string(key);
    if (!v) fail_missing(key, "a string");
    return *v;
  }
  /// A string naming something (see name_problem), or `fallback` if absent.
  std::string name(const std::string& key, const std::string& fallback) {
    std::optional<std::string> v = optional_string(key);
    if (!v) return fallback;
    check_name(key, *v);
    return *v;
  }
  std::string required_name(const std::string& key) {
    std::string v = required_string(key);
    check_name(key, v);
    return v;
  }

  std::optional<std::int64_t> optional_integer(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_integer()) fail(key, "expected an integer");
    return node->value<std::int64_t>();
  }
  /// An integer in [low, high].
  std::optional<std::int64_t> optional_integer(const std::string& key, std::int64_t low, std::int64_t high) {
    const auto v = optional_integer(key);
    if (v && (*v < low || *v > high)) fail(key, fmt::format("must be between {} and {}, got {}", low, high, *v));
    return v;
  }
  std::int64_t required_integer(const std::string& key) {
    const auto v = optional_integer(key);
    if (!v) fail_missing(key, "an integer");
    return *v;
  }

  std::optional<double> optional_number(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_number()) fail(key, "expected a number");
    return node->value<double>();
  }

  std::optional<bool> optional_bool(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_boolean()) fail(key, "expected true or false");
    return node->value<bool>();
  }

  /// A size: a string with units ("3 GB", "3 GiB") or a number of bytes (rounded), at most
  /// units::kMaxBytes.
  std::optional<std::int64_t> optional_size(const std::string& key) {
    const auto bytes = with_units(key, Kind::Size);
    if (!bytes) return std::nullopt;
    return static_cast<std::int64_t>(*bytes);
  }
  /// A bandwidth: "465 MB/s", "10 Gbit/s", or a number of bytes per second of at least 10^6
  /// (a bare 465 is far more often "465 MB/s" without its unit than 465 B/s: "465 B/s" says
  /// that). At most units::kMaxBandwidth.
  std::optional<double> optional_bandwidth(const std::string& key) { return with_units(key, Kind::Bandwidth); }
  /// A duration: "30 s", "250 ms", or a number of seconds; at most units::kMaxSeconds.
  std::optional<double> optional_duration(const std::string& key) { return with_units(key, Kind::Duration); }
  std::int64_t required_size(const std::string& key) {
    auto v = optional_size(key);
    if (!v) fail_missing(key, "a size such as \"3 GB\"");
    return *v;
  }
  /// A bandwidth of at least units::kMinBandwidth.
  double required_bandwidth(const std::string& key) {
    auto v = optional_bandwidth(key);
    if (!v) fail_missing(key, "a bandwidth such as \"465 MB/s\"");
    if (*v < units::kMinBandwidth) fail(key, fmt::format("must be at least 1 B/s, got {} B/s", *v));
    return *v;
  }

  /// A string or an array of strings.
  std::vector<std::string> strings(const std::string& key) {
    const toml::node* node = take(key);
    std::vector<std::string> out;
    if (node == nullptr) return out;
    if (node->is_string()) {
      out.push_back(*node->value<std::string>());
      return out;
    }
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(key, "expected a string or an array of strings");
    for (const toml::node& item : *array) {
      if (!item.is_string()) fail(key, "expected an array of strings");
      out.push_back(*item.value<std::string>());
    }
    return out;
  }
  /// A name or a list of names (see name()).
  std::vector<std::string> names(const std::string& key) {
    std::vector<std::string> out = strings(key);
    for (const std::string& n : out) check_name(key, n);
    return out;
  }

  /// The key's node, of any type (nullptr if absent), marked as read.
  const toml::node* raw(const std::string& key) { return take(key); }

  const toml::table* optional_table(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return nullptr;
    if (!node->is_table()) fail(key, "expected a table");
    return node->as_table();
  }

  /// An array of tables ([[key]]); empty if absent.
  std::vector<const toml::table*> tables(const std::string& key) {
    const toml::node* node = take(key);
    std::vector<const toml::table*> out;
    if (node == nullptr) return out;
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(key, "expected an array of tables ([[" + full(key) + "]])");
    for (const toml::node& item : *array) {
      if (!item.is_table()) fail(key, "expected an array of tables ([[" + full(key) + "]])");
      out.push_back(item.as_table());
    }
    return out;
  }

  std::string child_path(const std::string& key) const { return full(key); }
  std::string child_path(const std::string& key, std::size_t index) const { return fmt::format("{}[{}]", full(key), index); }

  /// Rejects the keys that were never read, suggesting the known key each most resembles.
  void finish() const {
    for (const auto& [key, node] : *table_) {
      const std::string name(key.str());
      if (read_.count(name) == 0) {
        const std::string meant = formats::closest(name, read_);
        throw ConfigError(fmt::format("{}: unknown key '{}'{}", location(node.source(), *file_), full(name),
                                      meant.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", full(meant))),
                          input_place(node.source(), *file_, full(name)));
      }
    }
  }

 private:
  enum class Kind { Size, Bandwidth, Duration };

  std::string full(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const toml::node* take(const std::string& key) {
    read_.insert(key);
    return table_->get(key);
  }

  void check_name(const std::string& key, const std::string& value) const {
    const std::string problem = formats::name_problem(value);
    if (!problem.empty()) fail(key, problem);
  }

  // A missing key is often a misspelt one: the unknown key most like it is named instead.
  [[noreturn]] void fail_missing(const std::string& key, const char* what) const {
    std::set<std::string> unknown;
    for (const auto& [k, node] : *table_) {
      if (read_.count(std::string(k.str())) == 0) unknown.insert(std::string(k.str()));
    }
    const std::string typo = formats::closest(key, unknown);
    if (!typo.empty()) {
      const toml::node* node = table_->get(typo);
      throw ConfigError(fmt::format("{}: unknown key '{}' (did you mean '{}'?)", location(node->source(), *file_), full(typo), full(key)),
                        input_place(node->source(), *file_, full(typo)));
    }
    throw ConfigError(fmt::format("{}: missing key '{}' ({})", location(table_->source(), *file_), full(key), what),
                      input_place(table_->source(), *file_, full(key)));
  }

  std::optional<double> with_units(const std::string& key, Kind kind) {
    static constexpr const char* kWhat[] = {"a size such as \"3 GB\"", "a bandwidth such as \"465 MB/s\"", "a duration such as \"30 s\""};
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    double value = 0.0;
    if (node->is_number()) {
      value = *node->value<double>();
      if (std::isnan(value)) fail(key, std::string("expected ") + kWhat[static_cast<int>(kind)] + ", got nan");
      if (value < 0.0) fail(key, fmt::format("must not be negative, got {}", value));
      if (kind == Kind::Bandwidth && value >= units::kMinBandwidth && value < 1e6) {
        fail(key, fmt::format("a bare number is bytes per second: {0} is {0} B/s; write \"{0} MB/s\" if that is meant, or "
                              "\"{0} B/s\" to keep it",
                              value));
      }
    } else if (node->is_string()) {
      try {
        value = kind == Kind::Size        ? static_cast<double>(units::parse_size(*node->value<std::string>()))
                : kind == Kind::Bandwidth ? units::parse_bandwidth(*node->value<std::string>())
                                          : units::parse_duration(*node->value<std::string>());
      } catch (const ConfigError& e) {
        fail(key, e.what());
      }
    } else {
      fail(key, std::string("expected ") + kWhat[static_cast<int>(kind)]);
    }
    switch (kind) {
      case Kind::Size:
        value = std::round(value);
        if (!(value <= static_cast<double>(units::kMaxBytes))) fail(key, fmt::format("{} bytes is too large (at most 1 EiB)", value));
        break;
      case Kind::Bandwidth:
        if (!(value <= units::kMaxBandwidth)) fail(key, fmt::format("{} B/s is too fast (at most 1 PB/s)", value));
        break;
      case Kind::Duration:
        if (!(value <= units::kMaxSeconds)) {
          fail(key, fmt::format("{} s is too long (at most 1e9 s, about 32 years: simulated time keeps the microsecond to there)", value));
        }
        break;
    }
    return value;
  }

  const toml::table* table_;
  std::string path_;
  const std::string* file_;
  std::set<std::string> read_;
};

}  // namespace pagecache::scenario
