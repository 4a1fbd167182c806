// The policies a CacheSettings may name. A new policy is a file in this folder defining its
// factory, and a line here.

#include "cache/policy.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace pagecache::cache {

std::unique_ptr<Policy> make_kernel_policy(const CacheSettings& settings);
std::unique_ptr<Policy> make_wrench_cache_policy(const CacheSettings& settings);
std::unique_ptr<Policy> make_lru_policy(const CacheSettings& settings);

namespace {

struct Registration {
  const char* name;
  std::unique_ptr<Policy> (*make)(const CacheSettings&);
};

constexpr Registration kPolicies[] = {
    {"kernel", &make_kernel_policy},
    {"wrench_cache", &make_wrench_cache_policy},
    {"lru", &make_lru_policy},
};

}  // namespace

std::unique_ptr<Policy> make_policy(const CacheSettings& settings) {
  for (const Registration& r : kPolicies) {
    if (settings.policy == r.name) return r.make(settings);
  }
  throw ConfigError(fmt::format("unknown page-cache policy '{}' (known: {})", settings.policy, fmt::join(cache_policy_names(), ", ")));
}

}  // namespace pagecache::cache

std::vector<std::string> pagecache::cache_policy_names() {
  std::vector<std::string> names;
  for (const cache::Registration& r : cache::kPolicies) names.emplace_back(r.name);
  return names;
}
