#include "report/csv_field.hpp"

namespace pagecache::report::detail {

void append_special_csv_field(fmt::memory_buffer& out, std::string_view text) {
  bool quoted = text.front() == ' ' || text.back() == ' ';
  for (char c : text) quoted = quoted || kQuotedByte[static_cast<unsigned char>(c)];
  if (quoted) out.push_back('"');
  if (text::starts_formula(text)) out.push_back('\'');
  for (char c : text) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  if (quoted) out.push_back('"');
}

}  // namespace pagecache::report::detail
