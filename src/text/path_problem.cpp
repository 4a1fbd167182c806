#include "text/path_problem.hpp"

#include "text/printable.hpp"

#include <fmt/format.h>

namespace pagecache::text {

std::string path_message(std::string_view argument, std::string_view path, std::string_view why) {
  const std::string shown = printable(path);
  return argument.empty() ? fmt::format("{}: {}", shown, why) : fmt::format("{} {}: {}", argument, shown, why);
}

std::string path_message(std::string_view argument, std::string_view path, std::string_view what, std::error_code error) {
  return path_message(argument, path, what.empty() ? error.message() : fmt::format("{}: {}", what, error.message()));
}

std::string nul_problem(std::string_view path) {
  const std::size_t at = path.find('\0');
  return at == std::string_view::npos ? std::string() : fmt::format("holds a NUL character (byte {}), which no file name can", at);
}

}  // namespace pagecache::text
