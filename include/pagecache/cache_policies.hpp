#pragma once
// The page-cache policies, as each declares itself (src/cache/policies/, one file each): its
// name, what it is, and its parameters, [hosts.page_cache] keys of four kinds, with their defaults
// under each profile; and the host model's switches, which every policy keeps. The scenario reader, `pcsim show`, `pcsim validate --switch` and the
// docs' tests read these declarations rather than naming policies or switches.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pagecache {

/// What a policy's parameter holds, which says how a scenario writes it: a switch (true or
/// false), an integer, a size ("64 KiB") or a ratio (a number from 0 to 1).
enum class ParameterKind : std::uint8_t { Switch, Integer, Size, Ratio };

/// A parameter's value: a switch's bool, an integer's or a size's (bytes) std::int64_t, a
/// ratio's double.
using ParameterValue = std::variant<bool, std::int64_t, double>;

/// A parameter of a policy: one of its behaviours on or off, or a number it decides by.
struct PolicyParameter {
  std::string_view key;          ///< its [hosts.page_cache] key
  ParameterValue linux_default;  ///< its value under the linux profile
  ParameterValue paper_default;  ///< under the paper profile: WRENCH-cache's decision
  std::string_view doc;          ///< what it turns on or sets, in a line
  ParameterKind kind = ParameterKind::Switch;
  /// The values an integer, size or ratio may take, inclusive.
  double lowest = 0.0;
  double highest = 0.0;

  /// Whether `value` is of this parameter's kind and within its bounds.
  bool accepts(const ParameterValue& value) const noexcept;
};

/// `value` as a scenario writes it for a parameter of `kind`: true, 64, "64 KiB", 0.25.
std::string format_parameter(ParameterKind kind, const ParameterValue& value);
/// The name of a kind, for messages: "a switch", "an integer", "a size", "a ratio".
std::string_view kind_name(ParameterKind kind) noexcept;

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
