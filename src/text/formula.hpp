#pragma once
// What a spreadsheet opening a CSV file runs as a formula (OWASP "CSV injection"): a cell
// whose text starts with = + - @ TAB or CR. The loader refuses names starting so; the CSV
// writers defuse any that reach them (a scenario built in code skips the loader).

#include <array>
#include <string_view>

namespace pagecache::text {

/// Per byte: whether a cell starting with it is read as a formula.
inline constexpr auto kFormulaStart = [] {
  std::array<bool, 256> t{};
  for (unsigned char c : {'=', '+', '-', '@', '\t', '\r'}) t[c] = true;
  return t;
}();

inline bool starts_formula(std::string_view text) { return !text.empty() && kFormulaStart[static_cast<unsigned char>(text.front())]; }

}  // namespace pagecache::text
