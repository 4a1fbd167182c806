#include "formats/common/json_text.hpp"

#include "text/printable.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

namespace pagecache::formats {

namespace {

using nlohmann::json;

// The offset of the first '[' or '{' nested deeper than kMaxJsonDepth, if any. Exact for valid
// JSON (brackets inside strings do not count); for text that is not JSON either verdict is an
// error, so it need not be.
std::optional<std::size_t> too_deep(std::string_view text) {
  std::size_t depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

// Records where the parser stopped: the document parser's exceptions carry no position for
// some errors (out_of_range 406, a number beyond a double), the SAX interface has it for all.
class ErrorPosition : public json::json_sax_t {
 public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string&, const json::exception& e) override {
    position_ = position;
    what_ = e.what();
    return false;
  }

  std::size_t position() const noexcept { return position_; }
  const std::string& what() const noexcept { return what_; }

 private:
  std::size_t position_ = 0;
  std::string what_;
};

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1,
// column 7: " prefix (its own line and column count a newline inside a string wrongly), cut
// short: the "last read" token it quotes can be a whole unterminated string.
std::string reason(std::string_view what) {
  if (!what.empty() && what.front() == '[') {
    const std::size_t end = what.find("] ");
    if (end != std::string_view::npos) what.remove_prefix(end + 2);
  }
  if (what.substr(0, 11) == "parse error") {
    const std::size_t colon = what.find(": ");
    if (colon != std::string_view::npos) what.remove_prefix(colon + 2);
  }
  constexpr std::size_t kLongest = 200;
  if (what.size() <= kLongest) return text::printable(what);
  std::size_t cut = kLongest;
  while (cut > 0 && (static_cast<unsigned char>(what[cut]) & 0xC0) == 0x80) --cut;  // a whole character
  return text::printable(what.substr(0, cut)) + "...";
}

}  // namespace

std::string line_column(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  std::size_t column = 1;
  for (std::size_t i = line_start; i < offset; ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // continuation bytes share their character's column
  }
  return fmt::format("{}:{}", line, column);
}

void check_unique_keys(std::string_view text, const std::string& file) {
  // The keys of each object open at this point (an array has none): valid JSON, so a string
  // right after '{' or after a ',' within an object is a key.
  struct Open {
    bool object;
    bool expect_key;
    std::unordered_set<std::string> keys;
  };
  std::vector<Open> open;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '{' || c == '[') {
      open.push_back(Open{c == '{', c == '{', {}});
    } else if ((c == '}' || c == ']') && !open.empty()) {
      open.pop_back();
    } else if (c == ',' && !open.empty()) {
      open.back().expect_key = open.back().object;
    } else if (c == '"') {
      const std::size_t start = i;
      bool escaped = false;
      for (++i; i < text.size() && (escaped || text[i] != '"'); ++i) escaped = !escaped && text[i] == '\\';
      if (open.empty() || !open.back().expect_key) continue;
      open.back().expect_key = false;
      const std::string_view raw = text.substr(start, i + 1 - start);
      // Escapes decoded, so that two spellings of one key are one key.
      std::string key = raw.find('\\') == std::string_view::npos ? std::string(raw.substr(1, raw.size() - 2)) : json::parse(raw).get<std::string>();
      if (!open.back().keys.insert(key).second) {
        throw ConfigError(fmt::format("{}:{}: key {} appears twice in one object (JSON readers differ on which one wins; pcsim takes neither)",
                                      file, line_column(text, start), reason("\"" + key + "\"")),
                          InputPlace{.file = file, .line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(start), '\n')), .key = key});
      }
    }
  }
}

json parse_json_text(const std::string& text, const std::string& file) {
  if (const auto deep = too_deep(text)) {
    throw ConfigError(fmt::format("{}:{}: JSON nested deeper than {} levels of arrays and objects (a workflow needs fewer than 10)",
                                  file, line_column(text, *deep), kMaxJsonDepth));
  }
  std::string what;
  try {
    json document = json::parse(text);
    check_unique_keys(text, file);
    return document;
  } catch (const json::exception& e) {
    what = e.what();
  }
  // Parsed again for the position: only on the way out, so valid files are parsed once.
  ErrorPosition error;
  json::sax_parse(text, &error);
  if (!error.what().empty()) what = error.what();
  // The parser counts the byte it failed on from 1 (the end of the text as one more byte).
  const std::size_t offset = error.position() > 0 ? error.position() - 1 : 0;
  throw ConfigError(fmt::format("{}:{}: malformed JSON: {}", file, line_column(text, offset), reason(what)));
}

}  // namespace pagecache::formats
