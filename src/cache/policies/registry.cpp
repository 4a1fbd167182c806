// The policies a CacheSettings may name. A new policy is a file in this folder defining its
// declaration and factory, and a line here.

#include "cache/policy.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace pagecache::cache {

extern const PolicyDeclaration kKernelPolicy;
extern const PolicyDeclaration kWrenchCachePreset;
extern const PolicyDeclaration kLruPolicy;
extern const PolicyDeclaration kArcPolicy;
std::unique_ptr<Policy> make_kernel_policy(const CacheSettings& settings);
std::unique_ptr<Policy> make_lru_policy(const CacheSettings& settings);
std::unique_ptr<Policy> make_arc_policy(const CacheSettings& settings);

namespace {

struct Registration {
  const PolicyDeclaration* declaration;
  std::unique_ptr<Policy> (*make)(const CacheSettings&);  // none for a preset: its policy's
};

const Registration kPolicies[] = {
    {&kKernelPolicy, &make_kernel_policy},
    {&kWrenchCachePreset, nullptr},
    {&kLruPolicy, &make_lru_policy},
    {&kArcPolicy, &make_arc_policy},
};

const Registration* registration(std::string_view name) {
  const auto* r = std::find_if(std::begin(kPolicies), std::end(kPolicies), [&](const Registration& x) { return x.declaration->name == name; });
  return r == std::end(kPolicies) ? nullptr : r;
}

// The registered declarations, in order, for cache_policies().
const std::vector<PolicyDeclaration>& declarations() {
  static const std::vector<PolicyDeclaration> all = [] {
    std::vector<PolicyDeclaration> v;
    for (const Registration& r : kPolicies) v.push_back(*r.declaration);
    return v;
  }();
  return all;
}

}  // namespace

std::unique_ptr<Policy> make_policy(const CacheSettings& settings) {
  const Registration* r = registration(settings.policy);
  if (r == nullptr) {
    throw ConfigError(fmt::format("unknown page-cache policy '{}' (known: {})", settings.policy, fmt::join(cache_policy_names(), ", ")));
  }
  // A preset is its policy, whose parameters read the preset's values (CacheSettings::get).
  if (r->make == nullptr) r = registration(r->declaration->preset_of);
  return r->make(settings);
}

}  // namespace pagecache::cache

namespace pagecache {

const PolicyParameter* PolicyDeclaration::parameter(std::string_view key) const noexcept {
  const auto p = std::find_if(parameters.begin(), parameters.end(), [&](const PolicyParameter& x) { return x.key == key; });
  return p == parameters.end() ? nullptr : &*p;
}

std::span<const PolicyDeclaration> cache_policies() noexcept { return cache::declarations(); }

const PolicyDeclaration* find_cache_policy(std::string_view name) noexcept {
  const cache::Registration* r = cache::registration(name);
  return r == nullptr ? nullptr : r->declaration;
}

const PolicyDeclaration* cache_policy_with(std::string_view key) noexcept {
  for (const cache::Registration& r : cache::kPolicies) {
    if (r.declaration->parameter(key) != nullptr) return r.declaration;
  }
  return nullptr;
}

std::vector<std::string> cache_policy_names() {
  std::vector<std::string> names;
  for (const cache::Registration& r : cache::kPolicies) names.emplace_back(r.declaration->name);
  return names;
}

}  // namespace pagecache
