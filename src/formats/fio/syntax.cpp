#include "formats/fio/syntax.hpp"

#include "formats/common/text_file.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace pagecache::formats::fio {

namespace {

// fio reads a line with fgets into 8192 bytes (parse.h OPT_LEN_MAX): a longer line would be
// read as several, so it is refused instead.
constexpr std::size_t kMaxLine = 8191;
// fio keeps 255 characters of a header, ']' included.
constexpr std::size_t kMaxSectionName = 254;

bool is_blank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
bool is_blank_or_control(char c) {
  const auto u = static_cast<unsigned char>(c);
  return std::isspace(u) != 0 || std::iscntrl(u) != 0;
}

[[noreturn]] void fail_at(const std::string& file, int line, const std::string& key, const std::string& message) {
  throw ConfigError(where(file, line) + message, InputPlace{.file = file, .line = line, .key = key});
}

// ${NAME} replaced by the variable's value ("" if unset), as fio_option_dup_subs does; a "${"
// with no "}" after it stays as written.
std::string substitute(const std::string& line, const FioEnvironment& env, const std::string& file, int number) {
  std::string out;
  for (std::size_t i = 0; i < line.size();) {
    const std::size_t close = line.compare(i, 2, "${") == 0 ? line.find('}', i + 2) : std::string::npos;
    if (close == std::string::npos || close == i + 2) {
      out += line[i++];
      continue;
    }
    out += env(line.substr(i + 2, close - i - 2)).value_or("");
    i = close + 1;
  }
  // fio silently drops a value that would not fit its line buffer.
  if (out.size() > kMaxLine) fail_at(file, number, {}, fmt::format("the line is longer than fio's {} bytes once ${{VAR}} are substituted", kMaxLine));
  // fio replaces these with the running machine's figures (and pipes arithmetic through bc).
  for (const char* word : {"$pagesize", "$mb_memory", "$ncpus"}) {
    if (out.find(word) != std::string::npos) {
      fail_at(file, number, {}, fmt::format("'{}' stands for a figure of the machine fio runs on; write the number instead", word));
    }
  }
  return out;
}

struct Reader {
  const FioEnvironment& env;
  const FioLimits& limits;
  std::vector<RawSection> sections;
  std::vector<std::string> open_files;  // the include chain, for cycles
  int includes = 0;

  void read(std::string_view text, const std::string& file, int depth);
  void line(std::string_view raw, const std::string& file, int number, int depth);
  void include(const std::string& name, const std::string& file, int number, int depth);
  void option(const std::string& text, const std::string& file, int number, int depth);
};

// A line as fio keeps it: leading blanks dropped, cut at the first ';' or '#', trailing blanks
// and control characters dropped.
std::string stripped(std::string_view raw) {
  std::size_t begin = 0;
  while (begin < raw.size() && is_blank(raw[begin])) ++begin;
  std::string_view rest = raw.substr(begin);
  rest = rest.substr(0, std::min(rest.find(';'), rest.find('#')));
  while (!rest.empty() && is_blank_or_control(rest.back())) rest.remove_suffix(1);
  return std::string(rest);
}

void Reader::read(std::string_view text, const std::string& file, int depth) {
  if (text.find('\0') != std::string_view::npos) {
    const auto at = text.find('\0');
    fail_at(file, 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n')), {},
            "a NUL byte: not a text job file");
  }
  int number = 0;
  for (std::size_t begin = 0; begin <= text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    ++number;
    if (end - begin > kMaxLine) fail_at(file, number, {}, fmt::format("a line longer than fio's {} bytes", kMaxLine));
    line(text.substr(begin, end - begin), file, number, depth);
    begin = end + 1;
  }
}

void Reader::line(std::string_view raw, const std::string& file, int number, int depth) {
  const std::string text = stripped(raw);
  if (text.empty()) return;
  if (std::iscntrl(static_cast<unsigned char>(text.front())) != 0) fail_at(file, number, {}, "a line cannot begin with a control character");
  if (text.front() == '[') {
    if (depth > 0) fail_at(file, number, {}, "an included file cannot open a new section (fio: no new sections in included files)");
    // fio drops the header's last character whatever it is: '[job' would be a job named "jo".
    if (text.size() < 3 || text.back() != ']') fail_at(file, number, {}, fmt::format("section header '{}' must be '[name]'", text));
    std::string name = text.substr(1, text.size() - 2);
    if (name.size() > kMaxSectionName) fail_at(file, number, {}, fmt::format("a section name is at most {} characters (fio cuts it)", kMaxSectionName));
    const bool global = name.rfind("global", 0) == 0;
    sections.push_back(RawSection{.name = std::move(name), .line = number, .global = global, .options = {}});
    return;
  }
  if (text.rfind("include", 0) == 0) {
    if (sections.empty()) fail_at(file, number, "include", fmt::format("option '{}' outside a job section", text));
    // fio takes everything after "include" and one separator as the file name.
    if (text.size() < 9 || (text[7] != ' ' && text[7] != '\t' && text[7] != '=')) {
      fail_at(file, number, "include", "write 'include FILE': one space (or '=') between include and the file name");
    }
    include(text.substr(8), file, number, depth);
    return;
  }
  option(substitute(text, env, file, number), file, number, depth);
}

void Reader::include(const std::string& name, const std::string& file, int number, int depth) {
  if (depth + 1 > limits.max_include_depth) fail_at(file, number, "include", fmt::format("includes nest deeper than {}", limits.max_include_depth));
  if (++includes > limits.max_includes) fail_at(file, number, "include", fmt::format("more than {} includes in all", limits.max_includes));
  // fio tries the name as given, then relative to the including file's folder.
  std::string path = name;
  const std::size_t slash = file.rfind('/');
  if (::access(name.c_str(), F_OK) != 0 && slash != std::string::npos) path = file.substr(0, slash + 1) + name;
  std::error_code ignored;
  const std::string identity = std::filesystem::weakly_canonical(path, ignored).string();
  if (std::find(open_files.begin(), open_files.end(), identity) != open_files.end()) {
    fail_at(file, number, "include", fmt::format("include '{}' includes itself (a cycle)", name));
  }
  std::string text;
  try {
    text = read_text_file(path, "fio job file");
  } catch (const ConfigError& error) {
    fail_at(file, number, "include", fmt::format("cannot include '{}': {}", name, error.what()));
  }
  open_files.push_back(identity);
  read(text, path, depth + 1);
  open_files.pop_back();
}

void Reader::option(const std::string& text, const std::string& file, int number, int depth) {
  const std::size_t equals = text.find('=');
  RawOption option{.key = text.substr(0, equals), .value = {}, .bare = equals == std::string::npos, .file = file, .line = number, .included = depth > 0};
  if (!option.bare) option.value = text.substr(equals + 1);
  // Messages quote a line only as far as it is an option's name: a job file's line may be
  // anyone's text.
  std::string trimmed = option.key;
  while (!trimmed.empty() && is_blank(trimmed.back())) trimmed.pop_back();
  if (!option_shaped(trimmed)) {
    fail_at(file, number, {},
            sections.empty() ? "neither a [section] header nor an option line of a fio job file"
            : option.key.empty() ? "no option name before '='"
                                 : "not an option line of a fio job file (an option's name is letters, digits and '_')");
  }
  if (sections.empty()) fail_at(file, number, option.key, fmt::format("option '{}' outside a job section", trimmed));
  // Deliberate difference: fio trims the key but keeps the value's leading blanks, so 'bs = 4k'
  // is 4 bytes and 'rw = read' an error; pcsim refuses both.
  if (!option.bare && (is_blank(option.key.back()) || (!option.value.empty() && is_blank(option.value.front())))) {
    const std::string& key = trimmed;
    const std::size_t first = option.value.find_first_not_of(" \t\v\f\r");
    const std::string value = first == std::string::npos ? std::string() : option.value.substr(first);
    if (option.included) fail_at(file, number, key, fmt::format("write option '{}' without spaces around '=' (fio reads the spaces as part of the value)", key));
    fail_at(file, number, key, fmt::format("write '{}={}' without spaces around '=' (fio reads the spaces as part of the value)", key, value));
  }
  sections.back().options.push_back(std::move(option));
}

}  // namespace

std::string where(const std::string& file, int line) { return fmt::format("{}:{}: ", file, line); }

bool option_shaped(std::string_view key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; });
}

void fail(const RawOption& option, const std::string& message) { fail_at(option.file, option.line, option.key, message); }

std::vector<RawSection> read_sections(std::string_view text, const std::string& path, const FioEnvironment& env,
                                      const FioLimits& limits) {
  Reader reader{.env = env, .limits = limits, .sections = {}, .open_files = {}, .includes = 0};
  std::error_code ignored;
  reader.open_files.push_back(std::filesystem::weakly_canonical(path, ignored).string());
  reader.read(text, path, 0);
  return std::move(reader.sections);
}

}  // namespace pagecache::formats::fio
