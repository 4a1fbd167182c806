#pragma once
// TomlReader: reads one TOML table of a scenario with the project's units and rules, and
// remembers which keys it read, so that finish() can reject every key it does not know.
// Every error names the file, the line and column, and the key's full path.

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <toml++/toml.h>

#include <fmt/format.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace pagecache::scenario {

class TomlReader {
 public:
  TomlReader(const toml::table& table, std::string path, const std::string& file)
      : table_(&table), path_(std::move(path)), file_(&file) {}

  const std::string& path() const noexcept { return path_; }
  bool has(const std::string& key) const { return table_->contains(key); }

  /// "file:line:col: key 'path.key': message", for the key's node (or the table's).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const toml::node* node = table_->get(key);
    const toml::source_region& where = node != nullptr ? node->source() : table_->source();
    throw ConfigError(fmt::format("{}:{}:{}: key '{}': {}", *file_, where.begin.line, where.begin.column, full(key), message));
  }
  [[noreturn]] void fail_table(const std::string& message) const {
    const toml::source_region& where = table_->source();
    throw ConfigError(fmt::format("{}:{}:{}: {}: {}", *file_, where.begin.line, where.begin.column,
                                  path_.empty() ? std::string("scenario") : "'" + path_ + "'", message));
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

  std::optional<std::int64_t> optional_integer(const std::string& key) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (!node->is_integer()) fail(key, "expected an integer");
    return node->value<std::int64_t>();
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

  /// A size: a string with units ("3 GB", "3 GiB") or an integer number of bytes.
  std::optional<std::int64_t> optional_size(const std::string& key) { return with_units<std::int64_t>(key, &units::parse_size, "a size such as \"3 GB\""); }
  std::optional<double> optional_bandwidth(const std::string& key) {
    return with_units<double>(key, &units::parse_bandwidth, "a bandwidth such as \"465 MB/s\"");
  }
  std::optional<double> optional_duration(const std::string& key) {
    return with_units<double>(key, &units::parse_duration, "a duration such as \"30 s\"");
  }
  std::int64_t required_size(const std::string& key) {
    auto v = optional_size(key);
    if (!v) fail_missing(key, "a size such as \"3 GB\"");
    return *v;
  }
  double required_bandwidth(const std::string& key) {
    auto v = optional_bandwidth(key);
    if (!v) fail_missing(key, "a bandwidth such as \"465 MB/s\"");
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

  /// Rejects the keys that were never read.
  void finish() const {
    for (const auto& [key, node] : *table_) {
      const std::string name(key.str());
      if (read_.count(name) == 0) {
        const toml::source_region& where = node.source();
        throw ConfigError(fmt::format("{}:{}:{}: unknown key '{}'", *file_, where.begin.line, where.begin.column, full(name)));
      }
    }
  }

 private:
  std::string full(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const toml::node* take(const std::string& key) {
    read_.insert(key);
    return table_->get(key);
  }

  [[noreturn]] void fail_missing(const std::string& key, const char* what) const {
    const toml::source_region& where = table_->source();
    throw ConfigError(fmt::format("{}:{}:{}: missing key '{}' ({})", *file_, where.begin.line, where.begin.column, full(key), what));
  }

  template <class T, class Parse>
  std::optional<T> with_units(const std::string& key, Parse parse, const char* what) {
    const toml::node* node = take(key);
    if (node == nullptr) return std::nullopt;
    if (node->is_integer()) {
      const auto v = *node->value<std::int64_t>();
      if (v < 0) fail(key, fmt::format("must not be negative, got {}", v));
      return static_cast<T>(v);
    }
    if (node->is_floating_point()) {
      const auto v = *node->value<double>();
      if (!(v >= 0.0)) fail(key, fmt::format("must not be negative, got {}", v));
      return static_cast<T>(v);
    }
    if (!node->is_string()) fail(key, std::string("expected ") + what);
    try {
      return static_cast<T>(parse(*node->value<std::string>()));
    } catch (const ConfigError& e) {
      fail(key, e.what());
    }
  }

  const toml::table* table_;
  std::string path_;
  const std::string* file_;
  std::set<std::string> read_;
};

}  // namespace pagecache::scenario
