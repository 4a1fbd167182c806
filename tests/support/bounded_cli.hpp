#pragma once
// pcsim given hostile input, as a tester gives it: the real binary, checked to end within a
// time and a memory bound, and a refusal checked for its exit status and its words.

#include "support/child_process.hpp"

#include <catch2/catch.hpp>

#include <initializer_list>
#include <string>
#include <vector>

namespace pagecache::testing {

/// How much longer pcsim takes in this build than in a release one, so that a bound meant for
/// the release build is scaled by it: under the sanitizers (a Debug build, which also checks the
/// cache's invariants at every change) a refusal several times, a simulation some forty times
/// (validate of the paper's runs: 0.34 s in Release, 25 s there).
/// And the memory of a simulation: AddressSanitizer's shadow and its quarantine of freed
/// blocks (256 MB at most) ride on what it allocates (validate: 14 MB in Release, 272 MB there).
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kSlowdown = 10.0;
inline constexpr double kSimulationSlowdown = 100.0;
inline constexpr long kSimulationMemoryKb = 200 * 1024 + 256 * 1024;
#else
inline constexpr double kSlowdown = 1.0;
inline constexpr double kSimulationSlowdown = 1.0;
inline constexpr long kSimulationMemoryKb = 200 * 1024;
#endif

/// `pcsim <args>` in `cwd` (if given), checked to have ended within `seconds` and `max_kb` of
/// resident memory (200 MB by default).
inline ChildResult bounded_pcsim(std::vector<std::string> args, double seconds, const std::string& cwd = {}, long max_kb = 200 * 1024) {
  args.insert(args.begin(), PCSIM_BINARY);
  ChildResult r = run_child(args, 2.0 * seconds + 5.0, cwd);
  INFO(r.output);
  CHECK_FALSE(r.timed_out);
  CHECK(r.seconds < seconds);
  CHECK(r.max_rss_kb < max_kb);
  return r;
}

/// Exit status 2 and every fragment in the message.
inline void refused(const ChildResult& r, std::initializer_list<std::string> fragments) {
  INFO(r.output);
  CHECK(r.status == 2);
  for (const std::string& f : fragments) CHECK_THAT(r.output, Catch::Contains(f));
}

}  // namespace pagecache::testing
