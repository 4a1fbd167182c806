#pragma once
// Reading the elements of a SimGrid platform file with pugixml: line numbers, attribute
// checks, SimGrid values with units, and the messages that name the file, line, element and
// attribute ("FILE:LINE: <link id="l1"> attribute bandwidth: '-5MBps' is negative").

#include "formats/simgrid/xml/units.hpp"

#include <pugixml.hpp>

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pagecache::formats::simgrid {

/// A SimGrid quantity: how to parse it, and the unit a bare number is read in.
struct SgQuantity {
  double (*parse)(std::string_view);
  const char* base_unit;
};
inline constexpr SgQuantity kSgBandwidth{parse_sg_bandwidth, "Bps"};
inline constexpr SgQuantity kSgTime{parse_sg_time, "s"};
inline constexpr SgQuantity kSgSpeed{parse_sg_speed, "f"};

/// An attribute refused with a reason ("changes the host's speed over time").
using SgRefused = std::pair<std::string_view, std::string_view>;

class SgXml {
 public:
  /// `text` must outlive this; warnings are appended to `warnings`.
  SgXml(std::string_view text, std::string file, std::vector<std::string>& warnings);

  /// The line (from 1) where `node` starts.
  int line(const pugi::xml_node& node) const;
  int line_at(std::ptrdiff_t offset) const;
  const std::string& file() const { return file_; }

  /// Throws ConfigError "FILE:LINE: <e id="...">: problem".
  [[noreturn]] void fail(const pugi::xml_node& e, std::string_view problem) const;
  /// Throws ConfigError "FILE:LINE: <e id="..."> attribute NAME: problem".
  [[noreturn]] void fail_attribute(const pugi::xml_node& e, std::string_view name, std::string_view problem) const;
  /// Adds "FILE:LINE: <e id="...">: what" to the warnings.
  void warn(const pugi::xml_node& e, std::string_view what);

  /// Refuses an attribute given twice, one of `refused` with its reason, and any other not in
  /// `known` as unknown (suggesting the closest known one).
  void check_attributes(const pugi::xml_node& e, std::initializer_list<std::string_view> known,
                        std::span<const SgRefused> refused = {}) const;
  /// Refuses any child element or text, for elements SimGrid declares EMPTY.
  void check_empty(const pugi::xml_node& e) const;
  /// Calls `visit` on each child element in order, refusing text between them.
  template <typename Visit>
  void for_each_element(const pugi::xml_node& e, Visit&& visit) const {
    for (const pugi::xml_node& child : e.children()) {
      if (child.type() == pugi::node_element) {
        visit(child);
      } else {
        check_blank(e, child);
      }
    }
  }
  /// Refuses `child` of `parent`: "not supported" with the reason for an element SimGrid knows
  /// and pcsim does not read, else "unknown element" suggesting the closest of `expected`.
  [[noreturn]] void unexpected(const pugi::xml_node& child, const pugi::xml_node& parent, const std::set<std::string>& expected) const;

  /// The attribute's value, which must be present and not empty.
  std::string required(const pugi::xml_node& e, const char* name) const;
  /// The attribute's value, which must be present but may be empty (a cluster's prefix or
  /// suffix: "node-" + N + "").
  std::string present(const pugi::xml_node& e, const char* name) const;
  /// The attribute's value if present (maybe empty).
  std::optional<std::string> optional(const pugi::xml_node& e, const char* name) const;
  /// `text` (attribute `name` of `e`) as quantity `q`, warning as SimGrid does if it has no
  /// unit; refuses a negative, non-finite or malformed value, and 0 unless `zero_ok`.
  double quantity(const pugi::xml_node& e, const char* name, const SgQuantity& q, std::string_view text, bool zero_ok);
  /// `text` (attribute `name` of `e`) as a whole number in [low, high] ("2" or "2.0").
  long long whole_number(const pugi::xml_node& e, const char* name, std::string_view text, long long low, long long high) const;

 private:
  void check_blank(const pugi::xml_node& parent, const pugi::xml_node& child) const;
  std::string describe(const pugi::xml_node& e) const;
  std::string at(const pugi::xml_node& node) const;

  std::string_view text_;
  std::string file_;
  std::vector<std::string>& warnings_;
  // Lines are counted from the last offset asked for: the reader asks in document order, so
  // counting costs one pass over the text in all, and no table (a file of 64 MiB of newlines
  // would need 512 MiB of line starts).
  mutable std::size_t cursor_offset_ = 0;
  mutable int cursor_line_ = 1;
};

}  // namespace pagecache::formats::simgrid
