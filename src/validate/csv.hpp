#pragma once
// The reader of the validation data (validation/paper/) and of the measurements `validate
// --here` keeps: CSV with a header line naming the columns, comma-separated, no quoting, LF or
// CRLF line ends (some of the paper's files were written on Windows). Read as strictly as a
// scenario: every fault is a ConfigError naming the file, the line and the column.
// Header-only: the command-line tests read pcsim's outputs with it and link only pagecache.

#include "formats/common/text_file.hpp"
#include "text/printable.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pagecache::validate {

/// A field as a message shows it: control characters visible, at most 40 bytes of it.
inline std::string shown(std::string_view field) {
  return field.size() <= 40 ? text::printable(field) : text::printable(field.substr(0, 40)) + "...";
}

enum class Sign { Any, NotNegative, Positive };

/// A CSV table: a header line, then rows with as many fields as the header (blank lines are
/// skipped). The columns a reader asks for must be in the header, once each; others are allowed.
class CsvTable {
 public:
  class Row;

  /// `text` read as the file named `file` (in messages). `needed`: the columns the caller
  /// reads; `optional`: those it reads when the header has them (an older file's lack).
  CsvTable(std::string_view text, std::string file, const std::vector<std::string>& needed,
           const std::vector<std::string>& optional = {});
  /// The file at `path`, named by it; a file that cannot be read is refused the same way.
  static CsvTable read(const std::filesystem::path& path, const std::vector<std::string>& needed,
                       const std::vector<std::string>& optional = {});

  const std::string& file() const { return file_; }
  const std::vector<std::string>& header() const { return header_; }
  bool has(std::string_view column) const { return columns_.find(column) != columns_.end(); }
  std::size_t size() const { return rows_.size(); }
  Row row(std::size_t i) const;

 private:
  struct Line {
    int number = 0;
    std::vector<std::string> fields;
  };

  std::string file_;
  std::vector<std::string> header_;
  std::map<std::string, std::size_t, std::less<>> columns_;  // the needed and present optional ones
  std::vector<Line> rows_;
};

/// One row of a table, its fields checked as they are read.
class CsvTable::Row {
 public:
  int line() const { return line_->number; }

  /// The field, not empty.
  const std::string& text(std::string_view column) const {
    const std::string& field = raw(column);
    if (field.empty()) fail(column, "empty");
    return field;
  }

  /// The field, one of `allowed`.
  const std::string& one_of(std::string_view column, std::initializer_list<std::string_view> allowed) const {
    const std::string& field = raw(column);
    std::string list;
    for (const std::string_view a : allowed) {
      if (field == a) return field;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    fail(column, fmt::format("'{}', expected one of {}", shown(field), list));
  }

  /// A finite number (NaN and infinities refused) of the sign asked for.
  double number(std::string_view column, Sign sign = Sign::Any) const {
    const std::string& field = raw(column);
    if (field.empty()) fail(column, "empty, expected a number");
    // strtod, as std::stod before: the shipped figures read to the same doubles. It skips
    // leading blanks, which a field the number alone does not have.
    // Nor is a hexadecimal number ("0x10", "0x1p4"), which strtod reads too, a measurement's.
    const bool blank = field.front() == ' ' || field.front() == '\t' || field.find_first_of("xXpP") != std::string::npos;
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (blank || end != field.c_str() + field.size() || std::isnan(v)) fail(column, fmt::format("'{}' is not a number", shown(field)));
    if (std::isinf(v)) fail(column, fmt::format("'{}' is not a finite number", shown(field)));
    if (sign == Sign::NotNegative && v < 0.0) fail(column, fmt::format("'{}' is negative", shown(field)));
    if (sign == Sign::Positive && !(v > 0.0)) fail(column, fmt::format("'{}' is not above 0", shown(field)));
    return v;
  }

  /// A whole number written as one (digits, maybe a leading '-'), from `min` to `max`.
  std::int64_t whole(std::string_view column, std::int64_t min, std::int64_t max) const {
    const std::string& field = raw(column);
    if (field.empty()) fail(column, "empty, expected a whole number");
    std::int64_t v = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (error != std::errc() || end != field.data() + field.size()) fail(column, fmt::format("'{}' is not a whole number", shown(field)));
    if (v < min) fail(column, min == 0 ? fmt::format("'{}' is negative", shown(field)) : fmt::format("'{}' is below {}", shown(field), min));
    if (v > max) fail(column, fmt::format("'{}' is above {}", shown(field), max));
    return v;
  }

  /// Every field, in the header's order.
  const std::vector<std::string>& fields() const { return line_->fields; }

  /// Throws the ConfigError "FILE:LINE: column 'COLUMN': why".
  [[noreturn]] void fail(std::string_view column, const std::string& why) const {
    throw ConfigError(fmt::format("{}:{}: column '{}': {}", table_->file_, line(), column, why));
  }

 private:
  friend class CsvTable;
  Row(const CsvTable& table, const Line& line) : table_(&table), line_(&line) {}

  const std::string& raw(std::string_view column) const {
    const auto it = table_->columns_.find(column);
    // A column the reader did not ask for, or an optional one the file lacks: pcsim's bug.
    if (it == table_->columns_.end()) throw InvariantError(fmt::format("{}: column '{}' was not asked for", table_->file_, column));
    return line_->fields[it->second];
  }

  const CsvTable* table_;
  const Line* line_;
};

inline CsvTable::Row CsvTable::row(std::size_t i) const { return Row(*this, rows_.at(i)); }

inline CsvTable::CsvTable(std::string_view text, std::string file, const std::vector<std::string>& needed,
                          const std::vector<std::string>& optional)
    : file_(std::move(file)) {
  std::string expected;
  for (const std::string& c : needed) expected += (expected.empty() ? "" : ",") + c;
  std::size_t at = 0;
  int number = 0;
  // The next line without its line end; false at the end of the text.
  const auto next = [&](std::string_view& line) {
    if (at >= text.size()) return false;
    const std::size_t end = std::min(text.find('\n', at), text.size());
    line = text.substr(at, end - at);
    at = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  };
  const auto split = [](std::string_view line) {
    std::vector<std::string> fields;
    for (std::size_t from = 0;; ) {
      const std::size_t comma = line.find(',', from);
      fields.emplace_back(line.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from));
      if (comma == std::string_view::npos) return fields;
      from = comma + 1;
    }
  };

  std::string_view line;
  if (!next(line)) throw ConfigError(fmt::format("{}:1: the file is empty; expected a header line naming the columns {}", file_, expected));
  if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // a byte order mark, as spreadsheets write
  if (line.empty()) throw ConfigError(fmt::format("{}:1: no header line; expected one naming the columns {}", file_, expected));
  header_ = split(line);
  const auto find = [&](const std::string& column, bool required) {
    std::size_t found = header_.size();
    for (std::size_t i = 0; i < header_.size(); ++i) {
      if (header_[i] != column) continue;
      if (found != header_.size()) throw ConfigError(fmt::format("{}:1: column '{}' twice in the header", file_, column));
      found = i;
    }
    if (found != header_.size()) {
      columns_.emplace(column, found);
    } else if (required) {
      throw ConfigError(fmt::format("{}:1: no column '{}' in the header '{}' (expected the columns {})", file_, column, shown(line), expected));
    }
  };
  for (const std::string& c : needed) find(c, true);
  for (const std::string& c : optional) find(c, false);

  while (next(line)) {
    if (line.empty()) continue;
    Line row{number, split(line)};
    if (row.fields.size() != header_.size()) {
      throw ConfigError(fmt::format("{}:{}: {} fields, expected {} as in the header", file_, number, row.fields.size(), header_.size()));
    }
    rows_.push_back(std::move(row));
  }
}

/// A file's bytes: a regular file of at most 64 MiB (a FIFO or /dev/zero would be read for
/// ever); else a ConfigError naming it and why.
inline std::string read_text_file(const std::filesystem::path& path) { return formats::read_text_file(path.string(), "data file"); }

inline CsvTable CsvTable::read(const std::filesystem::path& path, const std::vector<std::string>& needed,
                               const std::vector<std::string>& optional) {
  return CsvTable(read_text_file(path), path.string(), needed, optional);
}

/// For tests reading pcsim's CSV outputs and the validation data: the rows as maps from the
/// header's names to the fields.
using CsvRow = std::map<std::string, std::string>;

inline std::vector<CsvRow> read_csv(const std::string& path) {
  const CsvTable table = CsvTable::read(path, {});
  std::vector<CsvRow> rows;
  for (std::size_t i = 0; i < table.size(); ++i) {
    CsvRow row;
    const std::vector<std::string>& fields = table.row(i).fields();
    for (std::size_t c = 0; c < fields.size(); ++c) row[table.header()[c]] = fields[c];
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace pagecache::validate
