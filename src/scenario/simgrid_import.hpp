#pragma once
// A SimGrid platform (read by read_simgrid_platform) as a scenario's hosts, disks, links and
// routes, with WRENCH-cache's conventions for what SimGrid has no words for: a disk mounted at
// /memory (or named "memory") is the host's memory, its bandwidths the memory's, and the host
// prop `ram` (else that disk's `size`) the memory's size.

#include <pagecache/scenario.hpp>

#include "scenario/origins.hpp"
#include "formats/simgrid/routing/platform.hpp"

#include <set>
#include <string>
#include <utility>

namespace pagecache::scenario {

/// Adds the platform's hosts (with the profile's page-cache settings; memory and memory
/// bandwidths 0 where the file does not give them) and links to `s`, their origins to
/// `origins`, and what is ignored to s.warnings.
void add_simgrid_platform(const formats::simgrid::SgPlatform& platform, Scenario& s, Origins& origins);

/// Adds the platform's routes between the `pairs` of different hosts that have one (in either
/// direction), once each: the routes a run uses, not the N^2 of a cluster.
void add_simgrid_routes(const formats::simgrid::SgPlatform& platform, const std::set<std::pair<std::string, std::string>>& pairs, Scenario& s);

/// Adds every route of the platform between different hosts (`pcsim show` of a platform alone),
/// one per pair of hosts: pcsim's routes serve both ways.
void add_all_simgrid_routes(const formats::simgrid::SgPlatform& platform, Scenario& s);

/// Adds the first `most` routes between different hosts (`pcsim show`'s summary of a large
/// platform); returns how many it added.
std::size_t add_example_simgrid_routes(const formats::simgrid::SgPlatform& platform, std::size_t most, Scenario& s);

/// Warns of the links of `s` that the platform gives more than the 1 PB/s pcsim models.
void add_link_warnings(const formats::simgrid::SgPlatform& platform, Scenario& s);

/// True if `host`'s disk is its memory by WRENCH-cache's convention.
bool is_memory_disk(const formats::simgrid::SgDisk& disk);

}  // namespace pagecache::scenario
