#include "formats/common/names.hpp"

#include "text/formula.hpp"
#include "text/utf8.hpp"

#include <fmt/format.h>

namespace pagecache::formats {

std::string name_problem(std::string_view name) {
  if (name.empty()) return "a name cannot be empty";
  for (std::size_t i = 0; i < name.size();) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f) return fmt::format("a name cannot hold a control character (U+{:04X} at byte {})", c, i);
    const text::Utf8Char next = text::next_utf8_char(name.substr(i));
    if (!next.valid) return fmt::format("a name must be UTF-8 text (byte {} is not)", i);
    i += next.length;
  }
  // Control characters are refused above, so this is = + - or @.
  if (text::starts_formula(name)) {
    return fmt::format("a name cannot start with '{}': a spreadsheet opening the CSV outputs would run it as a formula", name.front());
  }
  return {};
}

}  // namespace pagecache::formats
