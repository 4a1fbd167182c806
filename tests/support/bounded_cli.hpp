#pragma once
// pcsim given hostile input, as a tester gives it: the real binary, checked to end within a
// time and a memory bound, and a refusal checked for its exit status and its words.

#include "support/child_process.hpp"

#include <catch2/catch.hpp>

#include <initializer_list>
#include <string>
#include <vector>

namespace pagecache::testing {

/// How much longer a run takes in this build than in a release one: a Debug build under the
/// sanitizers several times, so that a bound meant for the release build is scaled by it.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kSlowdown = 10.0;
#else
inline constexpr double kSlowdown = 1.0;
#endif

/// `pcsim <args>` in `cwd` (if given), checked to have ended within `seconds` and 200 MB of
/// resident memory.
inline ChildResult bounded_pcsim(std::vector<std::string> args, double seconds, const std::string& cwd = {}) {
  args.insert(args.begin(), PCSIM_BINARY);
  ChildResult r = run_child(args, 2.0 * seconds + 5.0, cwd);
  INFO(r.output);
  CHECK_FALSE(r.timed_out);
  CHECK(r.seconds < seconds);
  CHECK(r.max_rss_kb < 200 * 1024);
  return r;
}

/// Exit status 2 and every fragment in the message.
inline void refused(const ChildResult& r, std::initializer_list<std::string> fragments) {
  INFO(r.output);
  CHECK(r.status == 2);
  for (const std::string& f : fragments) CHECK_THAT(r.output, Catch::Contains(f));
}

}  // namespace pagecache::testing
