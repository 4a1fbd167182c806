// CacheSettings' switches: the host model's, declared here, and the policy's, read through the
// declaration of the policy they belong to.

#include <pagecache/cache_policies.hpp>
#include <pagecache/cache_settings.hpp>
#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <iterator>

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

constexpr PolicyParameter kHostModelSwitches[] = {
    {"copies_hold_cores", false, false,
     "copies into and out of the page cache hold a core of their host, competing with computations (Memory::copy_on)"},
    {"large_folios", true, false,
     "the page cache allocates multi-page folios (mm/filemap.c), which single pages freed by buffers serve last; with free "
     "page reporting only (docs/model.md §6.16)"},
    {"numa_nodes", true, false,
     "a platform's [hosts.numa] splits the host into NUMA nodes: allocations local first, reclaim per node, remote copies slower "
     "(docs/model.md §6.20); off: one uniform memory, as in the paper"},
};
constexpr bool CacheSettings::*kHostModelFields[] = {&CacheSettings::copies_hold_cores, &CacheSettings::large_folios, &CacheSettings::numa_nodes};
static_assert(std::size(kHostModelSwitches) == std::size(kHostModelFields), "a field of CacheSettings for each switch");

// The field of the host model's switch `key`, or none.
bool CacheSettings::* host_model_field(std::string_view key) {
  for (std::size_t i = 0; i < std::size(kHostModelSwitches); ++i) {
    if (kHostModelSwitches[i].key == key) return kHostModelFields[i];
  }
  return nullptr;
}

}  // namespace

std::span<const PolicyParameter> host_model_switches() noexcept { return kHostModelSwitches; }

const PolicyParameter* find_host_model_switch(std::string_view key) noexcept {
  for (const PolicyParameter& p : kHostModelSwitches) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

void CacheSettings::set(std::string_view key, bool value) {
  if (bool CacheSettings::*field = host_model_field(key)) {
    this->*field = value;
    return;
  }
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
  if (bool CacheSettings::*field = host_model_field(key)) return this->*field;
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
