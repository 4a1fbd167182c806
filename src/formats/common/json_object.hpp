#pragma once
// JsonObject: one object of a JSON input read with the project's rules: typed values in a
// range, and every error naming the file, the object's JSON path (with what it describes,
// e.g. task 'x') and the key: "FILE: workflow.specification.tasks[3] (task 'x'): parents:
// unknown task 'y'". Keys nobody asks for are ignored: JSON inputs carry many (WfFormat's
// command, priority, energy...), and they cannot change a result.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache::formats {

/// `name` quoted for a message: control characters and ill-formed UTF-8 made visible, and
/// shortened past 100 bytes (an id can be a megabyte long).
std::string quote_name(std::string_view name);

class JsonObject {
 public:
  /// A view of `value`, an object, at `path` ("" for the top level) of `file`; both must outlive it.
  JsonObject(const nlohmann::json& value, std::string path, const std::string& file);

  const std::string& path() const noexcept { return path_; }
  const std::string& file() const noexcept { return *file_; }
  /// What the object describes, shown after its path in messages: "task 'x'".
  void describe(std::string what) { what_ = std::move(what); }
  /// The path of `key`: "workflow.specification" for key "specification" of "workflow".
  std::string path_of(std::string_view key) const;

  /// "FILE: PATH (WHAT): KEY: text", the form of every error and warning about `key`.
  std::string message(std::string_view key, std::string_view text) const;
  [[noreturn]] void fail(std::string_view key, std::string_view text) const;
  /// "FILE: PATH (WHAT): text", about the object as a whole.
  [[noreturn]] void fail_object(std::string_view text) const;

  /// The value at `key`, or nullptr.
  const nlohmann::json* find(std::string_view key) const;
  /// Which of `keys` is present ("" if none). Two present is an error: a file giving both
  /// `runtime` and `runtimeInSeconds` leaves it unclear which was meant.
  std::string_view one_of(std::initializer_list<std::string_view> keys) const;

  std::optional<std::string> optional_string(std::string_view key) const;
  /// A non-empty string.
  std::string required_string(std::string_view key, std::string_view what) const;
  /// A finite number in [low, high].
  std::optional<double> optional_number(std::string_view key, double low, double high) const;
  double required_number(std::string_view key, double low, double high, std::string_view what) const;
  /// A whole number in [low, high]; 2 and 2.0 are the same number, 2.5 is refused.
  std::optional<std::int64_t> optional_whole(std::string_view key, std::int64_t low, std::int64_t high) const;
  /// A whole number of bytes, at most units::kMaxBytes.
  std::int64_t required_bytes(std::string_view key, std::string_view what) const;
  /// A number of bytes, at most units::kMaxBytes, rounded to a whole byte (WfFormat's
  /// memoryInBytes is any number).
  std::optional<std::int64_t> optional_rounded_bytes(std::string_view key) const;

  std::optional<JsonObject> optional_object(std::string_view key) const;
  JsonObject required_object(std::string_view key, std::string_view what) const;
  /// The array at `key`, or nullptr.
  const nlohmann::json::array_t* optional_array(std::string_view key) const;
  const nlohmann::json::array_t& required_array(std::string_view key, std::string_view what) const;
  /// Item `index` of `array`, the array at `key`, which must be an object.
  JsonObject item(std::string_view key, const nlohmann::json::array_t& array, std::size_t index) const;
  /// The strings of the array at `key` (empty if absent), each non-empty; `what` names an item
  /// in messages ("a task id"). Views into the document.
  std::vector<std::string_view> strings(std::string_view key, std::string_view what) const;

 private:
  std::string where() const;

  const nlohmann::json* value_;
  std::string path_;
  std::string what_;
  const std::string* file_;
};

/// "a string", "an array", "a number", "null": the JSON type of `value`, for messages.
std::string_view a_type(const nlohmann::json& value);

}  // namespace pagecache::formats
