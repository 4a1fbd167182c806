#pragma once
// PC_ASSERT: invariant checks that stay on in every build. They are cheap comparisons; a
// broken invariant throws pagecache::InvariantError naming the condition and the place, so a
// test can report it and the command line can exit cleanly, instead of clamping it away.
// Expensive whole-structure validations are switched on at run time by their owners.

#include <pagecache/error.hpp>

#include <string>

namespace pagecache::detail {

[[noreturn]] void invariant_failed(const char* condition, const char* file, int line,
                                   const std::string& detail);

}  // namespace pagecache::detail

#define PC_ASSERT(cond)                                                            \
  do {                                                                             \
    if (!(cond)) [[unlikely]]                                                      \
      ::pagecache::detail::invariant_failed(#cond, __FILE__, __LINE__, {});        \
  } while (false)

#define PC_ASSERT_MSG(cond, msg)                                                   \
  do {                                                                             \
    if (!(cond)) [[unlikely]]                                                      \
      ::pagecache::detail::invariant_failed(#cond, __FILE__, __LINE__, (msg));     \
  } while (false)
