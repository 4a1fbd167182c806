// The policies a CacheSettings may name. A new policy is a file in this folder defining its
// registration, and its name in PAGECACHE_CACHE_POLICIES.

#include "cache/policy.hpp"

#include <pagecache/cache_policies.hpp>
#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>


namespace pagecache::cache {

// The registered policies, in the order `pcsim show` and the docs list them: each one a
// registration (PolicyRegistration) its file defines.
#define PAGECACHE_CACHE_POLICIES(X) X(kKernelPolicy) X(kWrenchCachePreset) X(kLruPolicy) X(kArcPolicy) X(kClockPolicy) X(kMglruPolicy)

#define PAGECACHE_DECLARE(policy) extern const PolicyRegistration policy;
PAGECACHE_CACHE_POLICIES(PAGECACHE_DECLARE)
#undef PAGECACHE_DECLARE

namespace {

#define PAGECACHE_ADDRESS(policy) &policy,
const PolicyRegistration* const kPolicies[] = {PAGECACHE_CACHE_POLICIES(PAGECACHE_ADDRESS)};
#undef PAGECACHE_ADDRESS

const PolicyRegistration* registration(std::string_view name) {
  for (const PolicyRegistration* r : kPolicies) {
    if (r->declaration.name == name) return r;
  }
  return nullptr;
}

// The registered declarations, in order, for cache_policies().
const std::vector<PolicyDeclaration>& declarations() {
  static const std::vector<PolicyDeclaration> all = [] {
    std::vector<PolicyDeclaration> v;
    for (const PolicyRegistration* r : kPolicies) v.push_back(r->declaration);
    return v;
  }();
  return all;
}

}  // namespace

std::unique_ptr<Policy> make_policy(const CacheSettings& settings) {
  const PolicyRegistration* r = registration(settings.policy);
  if (r == nullptr) {
    throw ConfigError(fmt::format("unknown page-cache policy '{}' (known: {})", settings.policy, fmt::join(cache_policy_names(), ", ")));
  }
  // A preset is its policy, whose parameters read the preset's values (CacheSettings::get).
  if (r->make == nullptr) r = registration(r->declaration.preset_of);
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
  const cache::PolicyRegistration* r = cache::registration(name);
  return r == nullptr ? nullptr : &r->declaration;
}

const PolicyDeclaration* cache_policy_with(std::string_view key) noexcept {
  for (const cache::PolicyRegistration* r : cache::kPolicies) {
    if (r->declaration.parameter(key) != nullptr) return &r->declaration;
  }
  return nullptr;
}

std::vector<std::string> cache_policy_names() {
  std::vector<std::string> names;
  for (const cache::PolicyRegistration* r : cache::kPolicies) names.emplace_back(r->declaration.name);
  return names;
}

}  // namespace pagecache
