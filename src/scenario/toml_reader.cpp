#include "scenario/toml_reader.hpp"


namespace pagecache::scenario {

std::string location(const toml::source_region& where, const std::string& file) {
  if (where.path != nullptr) {
    // An override's value is parsed with the option as its source (loader.cpp).
    if (where.path->rfind("--set ", 0) == 0) return *where.path;
    return fmt::format("{}:{}:{}", *where.path, where.begin.line, where.begin.column);
  }
  // A table that --set made on its way to a key has no place in any file.
  if (where.begin.line == 0) return file + " (--set)";
  return fmt::format("{}:{}:{}", file, where.begin.line, where.begin.column);
}

std::string name_problem(std::string_view name) {
  if (name.empty()) return "a name cannot be empty";
  for (std::size_t i = 0; i < name.size();) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f) return fmt::format("a name cannot hold a control character (U+{:04X} at byte {})", c, i);
    // UTF-8: the length of the sequence from its first byte, then its continuation bytes, no
    // overlong forms, no surrogates, nothing above U+10FFFF.
    std::size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    bool valid = length != 0 && i + length <= name.size();
    std::uint32_t code = length == 1 ? c : length == 2 ? c & 0x1fu : length == 3 ? c & 0x0fu : c & 0x07u;
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(name[i + k]);
      valid = (next >> 6) == 0x2;
      code = (code << 6) | (next & 0x3fu);
    }
    if (valid && length > 1) {
      static constexpr std::uint32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
      valid = code >= kSmallest[length] && code <= 0x10ffff && !(code >= 0xd800 && code <= 0xdfff);
    }
    if (!valid) return fmt::format("a name must be UTF-8 text (byte {} is not)", i);
    i += length;
  }
  switch (name.front()) {
    case '=':
    case '+':
    case '-':
    case '@':
      return fmt::format("a name cannot start with '{}': a spreadsheet opening the CSV outputs would run it as a formula", name.front());
    default:
      return {};
  }
}

}  // namespace pagecache::scenario
