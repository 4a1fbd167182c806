// --set KEY=VALUE: a scenario's document changed before anything in it is read, so that a value
// given on the command line is checked, and named in messages, as the file's own are.

#include "scenario/loader_sections.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <sstream>

namespace pagecache::scenario {

namespace {

// An index into an array for --set: digits only ("-1" or "+1" is no index), below `size`.
std::size_t array_index(const std::string& part, std::size_t size, const std::string& key, const std::string& source) {
  std::size_t index = 0;
  const char* end = part.data() + part.size();
  const auto [stop, error] = std::from_chars(part.data(), end, index);
  if (part.empty() || error != std::errc() || stop != end) {
    throw ConfigError(fmt::format("{}: --set '{}': '{}' is not an index into an array of {} (0 to {})", source, key, part, size,
                                  size == 0 ? std::string("none") : std::to_string(size - 1)));
  }
  if (index >= size) {
    throw ConfigError(fmt::format("{}: --set '{}': index {} is out of range (the array has {} element{})", source, key, index, size,
                                  size == 1 ? "" : "s"));
  }
  return index;
}

// --set KEY=VALUE: VALUE is read as a TOML value (16, 0.4, true, "50 GB"); anything that is not
// valid TOML is taken as a string, so --set pipelines.file_size=50GB works too.
toml::node_view<toml::node> ensure_path(toml::table& root, const std::string& key, const std::string& source, const std::string& option) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  if (parts.empty() || key.back() == '.' || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    throw ConfigError(fmt::format("{}: --set '{}': not a dotted key such as pipelines.count", source, key));
  }
  toml::node* node = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (auto* table = node->as_table()) {
      // A table made on the way to the key has the option as its source, as the value has.
      if (!table->contains(part)) table->insert(part, std::move(*toml::parse("v = {}", option).get_as<toml::table>("v")));
      node = table->get(part);
    } else if (auto* array = node->as_array()) {
      node = array->get(array_index(part, array->size(), key, source));
    } else {
      throw ConfigError(fmt::format("{}: --set '{}': '{}' is not a table", source, key, part));
    }
  }
  return toml::node_view<toml::node>(node);
}

}  // namespace

void apply_override(toml::table& root, const std::string& key, const std::string& value, const std::string& source) {
  // Parsed with the option as its source, so that a problem with the value names the option.
  const std::string option = fmt::format("--set {}={}", key, value);
  auto parent = ensure_path(root, key, source, option);
  const std::string last = key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, option);
  } catch (const toml::parse_error&) {
    // Not a TOML value: a string, written as a TOML string so that it has the option as its
    // source too.
    std::string quoted = "v = \"";
    for (const char c : value) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') quoted += '\\';
      if (byte < 0x20 || byte == 0x7f) quoted += fmt::format("\\u{:04X}", byte);
      else quoted += c;
    }
    try {
      parsed = toml::parse(quoted + "\"", option);
    } catch (const toml::parse_error& e) {
      throw ConfigError(fmt::format("{}: the value is not a TOML value, nor text ({})", option, e.description()));
    }
  }
  if (auto* table = parent.as_table()) {
    table->insert_or_assign(last, std::move(*parsed.get("v")));
  } else if (auto* array = parent.as_array()) {
    const std::size_t index = array_index(last, array->size(), key, source);
    array->replace(array->begin() + static_cast<std::ptrdiff_t>(index), std::move(*parsed.get("v")));
  } else {
    throw ConfigError(fmt::format("{}: --set '{}': cannot set a key there", source, key));
  }
}

Overrides apply_overrides(toml::table& root, const Overrides& overrides, const std::string& source) {
  // A key of the platform's hosts, links or routes, in a scenario that takes them from a
  // platform file, changes that file's table (as read for this run only).
  Overrides of_platform;
  for (const auto& [key, value] : overrides) {
    const std::string first = key.substr(0, key.find('.'));
    const bool platform_part = first == "hosts" || first == "links" || first == "routes";
    if (platform_part && key != first && !root.contains(first) && root.contains("platform")) of_platform.emplace_back(key, value);
    else apply_override(root, key, value, source);
  }
  return of_platform;
}

}  // namespace pagecache::scenario
