#pragma once
// The page-cache policies, as each declares itself (src/cache/policies/, one file each): its
// name, what it is, and its parameters, the [hosts.page_cache] switches, with their defaults
// under each profile; and the host model's switches, which every policy keeps. The scenario reader, `pcsim show`, `pcsim validate --switch` and the
// docs' tests read these declarations rather than naming policies or switches.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pagecache {

/// A switch of a policy: one of its behaviours, on or off.
struct PolicyParameter {
  std::string_view key;  ///< its [hosts.page_cache] key
  bool linux_default;    ///< its value under the linux profile
  bool paper_default;    ///< under the paper profile: WRENCH-cache's decision
  std::string_view doc;  ///< what it turns on, in a line
};

/// A registered policy. A preset (`preset_of` not empty) owns no parameters: it is that policy
/// with every parameter at its paper default; setting one makes it that policy.
struct PolicyDeclaration {
  std::string_view name;
  std::string_view doc;
  std::span<const PolicyParameter> parameters;
  std::string_view preset_of;

  /// This policy's parameter `key`, or none.
  const PolicyParameter* parameter(std::string_view key) const noexcept;
};

/// The host model's switches (CacheSettings::copies_hold_cores, large_folios, numa_nodes):
/// [hosts.page_cache] keys of every policy, declared as a policy's parameters are.
std::span<const PolicyParameter> host_model_switches() noexcept;
/// The host model's switch `key`, or none.
const PolicyParameter* find_host_model_switch(std::string_view key) noexcept;

/// Every registered policy, in the order registered.
std::span<const PolicyDeclaration> cache_policies() noexcept;
/// The policy named `name`, or none.
const PolicyDeclaration* find_cache_policy(std::string_view name) noexcept;
/// The policy that declares the parameter `key`, or none.
const PolicyDeclaration* cache_policy_with(std::string_view key) noexcept;
/// The names of the registered policies, in the order registered.
std::vector<std::string> cache_policy_names();

}  // namespace pagecache
