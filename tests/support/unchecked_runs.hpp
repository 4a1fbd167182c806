#pragma once
// While alive, the page caches made set no invariant checks after each operation
// (PAGECACHE_CHECK_INVARIANTS=0, read when a PageCache is made). For tests that run whole
// scenarios of tens of thousands of operations: each check walks every block, and a debug
// build checks by default, which makes such a run quadratic.

#include <cstdlib>
#include <optional>
#include <string>

namespace pagecache::test {

class UncheckedRuns {
 public:
  UncheckedRuns() {
    if (const char* value = std::getenv(kName)) saved_ = value;
    ::setenv(kName, "0", 1);
  }
  ~UncheckedRuns() {
    if (saved_) ::setenv(kName, saved_->c_str(), 1);
    else ::unsetenv(kName);
  }
  UncheckedRuns(const UncheckedRuns&) = delete;
  UncheckedRuns& operator=(const UncheckedRuns&) = delete;

 private:
  static constexpr const char* kName = "PAGECACHE_CHECK_INVARIANTS";
  std::optional<std::string> saved_;
};

}  // namespace pagecache::test
