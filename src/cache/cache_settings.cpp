// CacheSettings' parameters, read through the declaration of the policy they belong to.

#include <pagecache/cache_policies.hpp>
#include <pagecache/cache_settings.hpp>
#include <pagecache/error.hpp>

#include <fmt/format.h>

namespace pagecache {

namespace {

const PolicyDeclaration& declaration_of(const std::string& policy) {
  const PolicyDeclaration* d = find_cache_policy(policy);
  if (d == nullptr) throw ConfigError(fmt::format("unknown page-cache policy '{}'", policy));
  return *d;
}

[[noreturn]] void no_such_parameter(std::string_view key, const std::string& policy) {
  throw ConfigError(fmt::format("'{}' is not a parameter of the page-cache policy '{}'", key, policy));
}

}  // namespace

void CacheSettings::set(std::string_view key, bool value) {
  const PolicyDeclaration& d = declaration_of(policy);
  if (!d.preset_of.empty()) {
    const PolicyDeclaration& base = declaration_of(std::string(d.preset_of));
    if (base.parameter(key) == nullptr) no_such_parameter(key, policy);
    for (const PolicyParameter& p : base.parameters) parameters.try_emplace(std::string(p.key), p.paper_default);
    policy = std::string(base.name);
  } else if (d.parameter(key) == nullptr) {
    no_such_parameter(key, policy);
  }
  parameters.insert_or_assign(std::string(key), value);
}

bool CacheSettings::get(std::string_view key) const {
  if (const auto given = parameters.find(key); given != parameters.end()) return given->second;
  const PolicyDeclaration& d = declaration_of(policy);
  if (!d.preset_of.empty()) {
    const PolicyParameter* p = declaration_of(std::string(d.preset_of)).parameter(key);
    if (p == nullptr) no_such_parameter(key, policy);
    return p->paper_default;
  }
  const PolicyParameter* p = d.parameter(key);
  if (p == nullptr) no_such_parameter(key, policy);
  return p->linux_default;
}

}  // namespace pagecache
