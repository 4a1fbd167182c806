#include "formats/simgrid/xml/elements.hpp"

#include <pagecache/error.hpp>

#include "formats/common/closest.hpp"
#include "formats/simgrid/xml/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace pagecache::formats::simgrid {

namespace {

// Elements SimGrid knows that pcsim does not read, and why.
constexpr std::pair<std::string_view, std::string_view> kUnsupported[] = {
    {"trace_connect", "not supported: it connects a profile that changes a host or link over time"},
    {"actor", "not supported: a deployment element (the scenario gives the workload)"},
    {"process", "not supported: a deployment element (the scenario gives the workload)"},
    {"argument", "not supported: a deployment element (the scenario gives the workload)"},
    {"peer", "not supported: peers belong to Vivaldi zones"},
    {"storage", "not supported: removed in SimGrid 3.27 (use <disk>)"},
    {"storage_type", "not supported: removed in SimGrid 3.27 (use <disk>)"},
    {"mount", "not supported: removed in SimGrid 3.27 (use <disk>)"},
    {"include", "not supported: removed in SimGrid 3.18"},
};

// Elements pcsim reads, somewhere.
constexpr std::string_view kRead[] = {"platform", "config", "random", "zone", "AS", "cluster", "host", "disk", "prop", "link", "route", "link_ctn",
                                      "router", "zoneRoute", "ASroute", "bypassRoute", "bypassZoneRoute", "bypassASroute", "host_link", "backbone", "cabinet", "trace"};

bool blank(const char* s) { return std::strspn(s, " \t\r\n") == std::strlen(s); }

}  // namespace

SgXml::SgXml(std::string_view text, std::string file, std::vector<std::string>& warnings)
    : text_(text), file_(std::move(file)), warnings_(warnings) {}

int SgXml::line_at(std::ptrdiff_t offset) const {
  const std::size_t to = std::min(static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0)), text_.size());
  const auto newlines = [this](std::size_t from, std::size_t until) {
    return static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(from), text_.begin() + static_cast<std::ptrdiff_t>(until), '\n'));
  };
  cursor_line_ += to >= cursor_offset_ ? newlines(cursor_offset_, to) : -newlines(to, cursor_offset_);
  cursor_offset_ = to;
  return cursor_line_;
}

int SgXml::line(const pugi::xml_node& node) const { return line_at(node.offset_debug()); }

std::string SgXml::describe(const pugi::xml_node& e) const {
  std::string s = fmt::format("<{}", sg_shown(e.name()));
  // An id names the element; a route has none, its ends name it.
  const auto add = [&](const char* key) {
    if (const pugi::xml_attribute a = e.attribute(key)) s += fmt::format(" {}=\"{}\"", key, sg_shown(a.value()));
  };
  if (e.attribute("id")) {
    add("id");
  } else {
    add("src");
    add("dst");
  }
  return s + ">";
}

std::string SgXml::at(const pugi::xml_node& node) const { return fmt::format("{}:{}", file_, line(node)); }

void SgXml::fail(const pugi::xml_node& e, std::string_view problem) const {
  throw ConfigError(fmt::format("{}: {}: {}", at(e), describe(e), problem));
}

void SgXml::fail_attribute(const pugi::xml_node& e, std::string_view name, std::string_view problem) const {
  throw ConfigError(fmt::format("{}: {} attribute {}: {}", at(e), describe(e), sg_shown(name), problem));
}

void SgXml::warn(const pugi::xml_node& e, std::string_view what) { warnings_.push_back(fmt::format("{}: {}: {}", at(e), describe(e), what)); }

void SgXml::check_attributes(const pugi::xml_node& e, std::initializer_list<std::string_view> known,
                             std::span<const SgRefused> refused) const {
  // Every attribute is first matched against `known`, so that a duplicate is found in time
  // linear in the attributes (a hostile element may have millions).
  std::vector<bool> seen(known.size());
  for (const pugi::xml_attribute& a : e.attributes()) {
    const std::string_view name = a.name();
    const auto found = std::find(known.begin(), known.end(), name);
    if (found != known.end()) {
      const auto i = static_cast<std::size_t>(found - known.begin());
      if (seen[i]) fail_attribute(e, name, "given twice");
      seen[i] = true;
      continue;
    }
    for (const auto& [refused_name, reason] : refused) {
      if (name == refused_name) fail_attribute(e, name, reason);
    }
    const std::string suggestion = closest(name, std::set<std::string>(known.begin(), known.end()));
    fail_attribute(e, name, suggestion.empty() ? "unknown attribute" : fmt::format("unknown attribute (did you mean {}?)", suggestion));
  }
}

void SgXml::check_blank(const pugi::xml_node& parent, const pugi::xml_node& child) const {
  if ((child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) && !blank(child.value())) {
    throw ConfigError(fmt::format("{}: {}: text is not allowed here", at(child), describe(parent)));
  }
}

void SgXml::check_empty(const pugi::xml_node& e) const {
  for_each_element(e, [&](const pugi::xml_node& child) { fail(child, fmt::format("not allowed inside <{}>, which holds nothing", e.name())); });
}

void SgXml::unexpected(const pugi::xml_node& child, const pugi::xml_node& parent, const std::set<std::string>& expected) const {
  const std::string_view name = child.name();
  for (const auto& [element, reason] : kUnsupported) {
    if (name == element) fail(child, reason);
  }
  if (std::find(std::begin(kRead), std::end(kRead), name) != std::end(kRead)) fail(child, fmt::format("not allowed inside <{}>", parent.name()));
  const std::string suggestion = closest(name, expected);
  fail(child, fmt::format("unknown element inside <{}>{}", parent.name(), suggestion.empty() ? "" : fmt::format(" (did you mean <{}>?)", suggestion)));
}

std::string SgXml::required(const pugi::xml_node& e, const char* name) const {
  const pugi::xml_attribute a = e.attribute(name);
  if (!a) fail_attribute(e, name, "missing");
  if (sg_trim(a.value()).empty()) fail_attribute(e, name, "empty");
  return a.value();
}

std::string SgXml::present(const pugi::xml_node& e, const char* name) const {
  const pugi::xml_attribute a = e.attribute(name);
  if (!a) fail_attribute(e, name, "missing");
  return a.value();
}

std::optional<std::string> SgXml::optional(const pugi::xml_node& e, const char* name) const {
  const pugi::xml_attribute a = e.attribute(name);
  if (!a) return std::nullopt;
  return std::string(a.value());
}

double SgXml::quantity(const pugi::xml_node& e, const char* name, const SgQuantity& q, std::string_view text, bool zero_ok) {
  double value = 0;
  try {
    value = q.parse(text);
  } catch (const ConfigError& error) {
    fail_attribute(e, name, error.what());
  }
  if (value == 0 && !zero_ok) fail_attribute(e, name, fmt::format("'{}': must be greater than 0", sg_shown(text)));
  if (sg_lacks_unit(text)) {
    warn(e, fmt::format("attribute {}: '{}' has no unit, read as {} (SimGrid does the same, warning that unit-less values are deprecated)", name,
                        sg_shown(text), q.base_unit));
  }
  return value;
}

long long SgXml::whole_number(const pugi::xml_node& e, const char* name, std::string_view text, long long low, long long high) const {
  const std::string_view s = sg_trim(text);
  double value = 0;
  const bool digit_first = !s.empty() && s.front() >= '0' && s.front() <= '9';
  const auto [end, error] = digit_first ? std::from_chars(s.data(), s.data() + s.size(), value)
                                        : std::from_chars_result{s.data(), std::errc::invalid_argument};
  if (error != std::errc() || end != s.data() + s.size() || value != std::floor(value) || value < static_cast<double>(low) ||
      value > static_cast<double>(high)) {
    fail_attribute(e, name, fmt::format("'{}' is not a whole number from {} to {}", sg_shown(text), low, high));
  }
  return static_cast<long long>(value);
}

}  // namespace pagecache::formats::simgrid
