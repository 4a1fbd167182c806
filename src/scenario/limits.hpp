#pragma once
// The checks of a whole resolved scenario against ScenarioLimits, made before it runs: its
// size, and estimates of its events, its simulated time and its memory profile. Each failure
// names the key that drives it, where it was written.

#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include "scenario/origins.hpp"

#include <string>

namespace pagecache::scenario {

/// Throws ConfigError if `s` is beyond `limits`.
void check_limits(const Scenario& s, const Origins& origins, const ScenarioLimits& limits);

/// ", without --force" when a limit is below what --force allows, so that messages say how to
/// go on when a scenario is big on purpose.
std::string limits_hint(const ScenarioLimits& limits);

}  // namespace pagecache::scenario
