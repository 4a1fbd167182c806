#include "formats/common/json_object.hpp"

#include "text/printable.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <cmath>

namespace pagecache::formats {

using nlohmann::json;

namespace {

// Beyond units::kMaxBytes, compared exactly: nlohmann keeps every non-negative integer unsigned.
bool too_many_bytes(const json& v) {
  return v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(units::kMaxBytes)
                                : v.get<double>() > static_cast<double>(units::kMaxBytes);
}

}  // namespace

std::string quote_name(std::string_view name) {
  constexpr std::size_t kLongest = 100;
  if (name.size() <= kLongest) return fmt::format("'{}'", text::printable(name));
  std::size_t cut = kLongest;
  while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;  // a whole character
  return fmt::format("'{}...' ({} bytes)", text::printable(name.substr(0, cut)), name.size());
}

std::string_view a_type(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "a value of another kind";
  }
}

JsonObject::JsonObject(const json& value, std::string path, const std::string& file)
    : value_(&value), path_(std::move(path)), file_(&file) {}

std::string JsonObject::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

std::string JsonObject::where() const {
  if (path_.empty()) return *file_;
  return what_.empty() ? fmt::format("{}: {}", *file_, path_) : fmt::format("{}: {} ({})", *file_, path_, what_);
}

std::string JsonObject::message(std::string_view key, std::string_view text) const { return fmt::format("{}: {}: {}", where(), key, text); }

void JsonObject::fail(std::string_view key, std::string_view text) const { throw ConfigError(message(key, text)); }

void JsonObject::fail_object(std::string_view text) const { throw ConfigError(fmt::format("{}: {}", where(), text)); }

const json* JsonObject::find(std::string_view key) const {
  const auto it = value_->find(key);
  return it == value_->end() ? nullptr : &*it;
}

std::string_view JsonObject::one_of(std::initializer_list<std::string_view> keys) const {
  std::string_view found;
  for (std::string_view key : keys) {
    if (find(key) == nullptr) continue;
    if (!found.empty()) fail(key, fmt::format("given together with '{}': give one of them", found));
    found = key;
  }
  return found;
}

std::optional<std::string> JsonObject::optional_string(std::string_view key) const {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_string()) fail(key, fmt::format("expected a string, got {}", a_type(*v)));
  return v->get_ref<const std::string&>();
}

std::string JsonObject::required_string(std::string_view key, std::string_view what) const {
  std::optional<std::string> v = optional_string(key);
  if (!v) fail(key, fmt::format("missing: {}", what));
  if (v->empty()) fail(key, "must not be empty");
  return std::move(*v);
}

std::optional<double> JsonObject::optional_number(std::string_view key, double low, double high) const {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_number()) fail(key, fmt::format("expected a number, got {}", a_type(*v)));
  const double x = v->get<double>();
  // The parser refuses what overflows a double, so x is finite here; NaN is no JSON number.
  if (low == 0 && x < 0) fail(key, fmt::format("must not be negative, got {}", v->dump()));
  if (!(x >= low && x <= high)) fail(key, fmt::format("must be between {} and {}, got {}", low, high, v->dump()));
  return x;
}

double JsonObject::required_number(std::string_view key, double low, double high, std::string_view what) const {
  const std::optional<double> v = optional_number(key, low, high);
  if (!v) fail(key, fmt::format("missing: {}", what));
  return *v;
}

std::optional<std::int64_t> JsonObject::optional_whole(std::string_view key, std::int64_t low, std::int64_t high) const {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_number()) fail(key, fmt::format("expected a whole number, got {}", a_type(*v)));
  if (v->is_number_float() && v->get<double>() != std::floor(v->get<double>())) {
    fail(key, fmt::format("must be a whole number, got {}", v->dump()));
  }
  if (low == 0 && v->get<double>() < 0) fail(key, fmt::format("must not be negative, got {}", v->dump()));
  // Each kind compared in its own type: a double or an unsigned beyond int64 does not convert.
  bool in_range = false;
  if (v->is_number_unsigned()) {
    in_range = v->get<std::uint64_t>() <= static_cast<std::uint64_t>(high) && static_cast<std::int64_t>(v->get<std::uint64_t>()) >= low;
  } else if (v->is_number_integer()) {
    in_range = v->get<std::int64_t>() >= low && v->get<std::int64_t>() <= high;
  } else {
    in_range = v->get<double>() >= static_cast<double>(low) && v->get<double>() <= static_cast<double>(high);
  }
  if (!in_range) fail(key, fmt::format("must be between {} and {}, got {}", low, high, v->dump()));
  return v->is_number_float() ? static_cast<std::int64_t>(v->get<double>()) : v->get<std::int64_t>();
}

std::int64_t JsonObject::required_bytes(std::string_view key, std::string_view what) const {
  const json* v = find(key);
  if (v == nullptr) fail(key, fmt::format("missing: {}", what));
  if (!v->is_number()) fail(key, fmt::format("expected a whole number of bytes, got {}", a_type(*v)));
  if (too_many_bytes(*v)) fail(key, fmt::format("{} bytes is too large (at most 2^60, 1 EiB)", v->dump()));
  return *optional_whole(key, 0, units::kMaxBytes);
}

std::optional<std::int64_t> JsonObject::optional_rounded_bytes(std::string_view key) const {
  const json* v = find(key);
  if (v != nullptr && v->is_number() && too_many_bytes(*v)) {
    fail(key, fmt::format("{} bytes is too large (at most 2^60, 1 EiB)", v->dump()));
  }
  const std::optional<double> bytes = optional_number(key, 0, static_cast<double>(units::kMaxBytes));
  if (!bytes) return std::nullopt;
  return static_cast<std::int64_t>(std::llround(*bytes));
}

std::optional<JsonObject> JsonObject::optional_object(std::string_view key) const {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_object()) fail(key, fmt::format("expected an object, got {}", a_type(*v)));
  return JsonObject(*v, path_of(key), *file_);
}

JsonObject JsonObject::required_object(std::string_view key, std::string_view what) const {
  std::optional<JsonObject> v = optional_object(key);
  if (!v) fail(key, fmt::format("missing: {}", what));
  return *v;
}

const json::array_t* JsonObject::optional_array(std::string_view key) const {
  const json* v = find(key);
  if (v == nullptr) return nullptr;
  if (!v->is_array()) fail(key, fmt::format("expected an array, got {}", a_type(*v)));
  return v->get_ptr<const json::array_t*>();
}

const json::array_t& JsonObject::required_array(std::string_view key, std::string_view what) const {
  const json::array_t* v = optional_array(key);
  if (v == nullptr) fail(key, fmt::format("missing: {}", what));
  return *v;
}

JsonObject JsonObject::item(std::string_view key, const json::array_t& array, std::size_t index) const {
  JsonObject out(array[index], fmt::format("{}[{}]", path_of(key), index), *file_);
  if (!array[index].is_object()) out.fail_object(fmt::format("expected an object, got {}", a_type(array[index])));
  return out;
}

std::vector<std::string_view> JsonObject::strings(std::string_view key, std::string_view what) const {
  std::vector<std::string_view> out;
  const json::array_t* array = optional_array(key);
  if (array == nullptr) return out;
  out.reserve(array->size());
  for (std::size_t i = 0; i < array->size(); ++i) {
    const json& v = (*array)[i];
    if (!v.is_string()) fail(key, fmt::format("item {} is {}, expected {} (a string)", i, a_type(v), what));
    const std::string& s = v.get_ref<const std::string&>();
    if (s.empty()) fail(key, fmt::format("item {} is an empty string, expected {}", i, what));
    out.push_back(s);
  }
  return out;
}

}  // namespace pagecache::formats
