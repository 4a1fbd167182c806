#include "engine/check.hpp"

#include <fmt/format.h>

namespace pagecache::detail {

void invariant_failed(const char* condition, const char* file, int line, const std::string& detail) {
  std::string message = fmt::format("invariant violated: {} ({}:{})", condition, file, line);
  if (!detail.empty()) message += ": " + detail;
  throw InvariantError(message);
}

}  // namespace pagecache::detail
