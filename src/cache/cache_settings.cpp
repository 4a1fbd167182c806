// CacheSettings' parameters: the host model's switches, declared here, and the policy's, of the
// kinds its declaration gives them, read and checked through it.

#include <pagecache/cache_policies.hpp>
#include <pagecache/cache_settings.hpp>
#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <iterator>
#include <variant>

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

// A bound as a value of `kind`.
ParameterValue to_kind(ParameterKind kind, double bound) {
  if (kind == ParameterKind::Ratio) return bound;
  return static_cast<std::int64_t>(bound);
}

// Throws ConfigError naming the parameter, its kind and bounds, unless it takes `value`.
void check_value(const PolicyParameter& p, const ParameterValue& value) {
  if (p.accepts(value)) return;
  if (p.kind == ParameterKind::Switch) throw ConfigError(fmt::format("'{}' is a switch: true or false", p.key));
  throw ConfigError(fmt::format("'{}' is {} from {} to {}, got {}", p.key, kind_name(p.kind), format_parameter(p.kind, to_kind(p.kind, p.lowest)),
                                format_parameter(p.kind, to_kind(p.kind, p.highest)), format_parameter(p.kind, value)));
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

void CacheSettings::set(std::string_view key, ParameterValue value) {
  if (bool CacheSettings::*field = host_model_field(key)) {
    if (!std::holds_alternative<bool>(value)) throw ConfigError(fmt::format("'{}' is a switch: true or false", key));
    this->*field = std::get<bool>(value);
    return;
  }
  const PolicyDeclaration& d = declaration_of(policy);
  const PolicyParameter* declared = nullptr;
  if (!d.preset_of.empty()) {
    const PolicyDeclaration& base = declaration_of(std::string(d.preset_of));
    declared = base.parameter(key);
    if (declared == nullptr) no_such_parameter(key, policy);
    check_value(*declared, value);
    for (const PolicyParameter& p : base.parameters) parameters.try_emplace(std::string(p.key), p.paper_default);
    policy = std::string(base.name);
  } else {
    declared = d.parameter(key);
    if (declared == nullptr) no_such_parameter(key, policy);
    check_value(*declared, value);
  }
  parameters.insert_or_assign(std::string(key), value);
}

ParameterValue CacheSettings::value(std::string_view key) const {
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

bool CacheSettings::get(std::string_view key) const {
  const ParameterValue v = value(key);
  if (!std::holds_alternative<bool>(v)) throw ConfigError(fmt::format("'{}' is not a switch of the page-cache policy '{}'", key, policy));
  return std::get<bool>(v);
}

std::int64_t CacheSettings::integer(std::string_view key) const {
  const ParameterValue v = value(key);
  if (!std::holds_alternative<std::int64_t>(v)) {
    throw ConfigError(fmt::format("'{}' is not an integer or a size of the page-cache policy '{}'", key, policy));
  }
  return std::get<std::int64_t>(v);
}

double CacheSettings::ratio(std::string_view key) const {
  const ParameterValue v = value(key);
  if (!std::holds_alternative<double>(v)) throw ConfigError(fmt::format("'{}' is not a ratio of the page-cache policy '{}'", key, policy));
  return std::get<double>(v);
}

bool PolicyParameter::accepts(const ParameterValue& value) const noexcept {
  switch (kind) {
    case ParameterKind::Switch: return std::holds_alternative<bool>(value);
    case ParameterKind::Integer:
    case ParameterKind::Size: {
      if (!std::holds_alternative<std::int64_t>(value)) return false;
      const auto v = static_cast<double>(std::get<std::int64_t>(value));
      return v >= lowest && v <= highest;
    }
    case ParameterKind::Ratio: {
      if (!std::holds_alternative<double>(value)) return false;
      const double v = std::get<double>(value);
      return v >= lowest && v <= highest;
    }
  }
  return false;
}

std::string_view kind_name(ParameterKind kind) noexcept {
  switch (kind) {
    case ParameterKind::Switch: return "a switch";
    case ParameterKind::Integer: return "an integer";
    case ParameterKind::Size: return "a size";
    case ParameterKind::Ratio: return "a ratio";
  }
  return "a parameter";
}

std::string format_parameter(ParameterKind kind, const ParameterValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const double* d = std::get_if<double>(&value)) return fmt::format("{}", *d);
  const std::int64_t n = std::get<std::int64_t>(value);
  return kind == ParameterKind::Size ? fmt::format("\"{}\"", units::format_size(n)) : fmt::format("{}", n);
}

}  // namespace pagecache
