#pragma once
// CacheSettings: how one host's page cache behaves (docs/model.md §3, §6).
//
// The kernel knobs keep the kernel's names and are stored in SI units (ratios as fractions,
// times in seconds). `policy` names the model of the decisions in which the kernel and
// WRENCH-cache, the paper's implementation, differ (docs/wrench-cache.md); each policy
// declares its parameters (pagecache/cache_policies.hpp). CacheSettings::paper() reproduces
// WRENCH-cache (the `paper` profile, policy `wrench_cache`); CacheSettings::kernel() follows
// the kernel (the `linux` profile; not named linux(), which GNU dialects of C++ predefine as
// a macro).

#include <pagecache/cache_policies.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace pagecache {

enum class WriteMode { Writeback, Writethrough };

struct CacheSettings {
  WriteMode write_mode = WriteMode::Writeback;
  /// vm.dirty_ratio: a writer may dirty at most this fraction of dirtyable memory.
  double dirty_ratio = 0.2;
  /// vm.dirty_background_ratio: above this fraction background writeback starts.
  double dirty_background_ratio = 0.1;
  /// vm.dirty_expire_centisecs, in seconds: dirty data older than this is written back.
  double dirty_expire = 30.0;
  /// vm.dirty_writeback_centisecs, in seconds: period of the flusher.
  double writeback_interval = 5.0;

  // The host model's switches (pagecache/cache_policies.hpp, host_model_switches): what the
  // host is made of, kept whatever the policy. On in the linux profile but copies_hold_cores,
  // off in the paper profile.
  /// Copies into and out of the page cache hold a core of their host (docs/model.md §6.15).
  bool copies_hold_cores = false;
  /// The page cache allocates multi-page folios, which single pages freed by buffers serve
  /// last (docs/model.md §6.16).
  bool large_folios = true;
  /// A platform's NUMA nodes are modelled (docs/model.md §6.20); off: one uniform memory.
  bool numa_nodes = true;

  /// The decisions' model, a registered policy (pagecache/cache_policies.hpp).
  std::string policy = "kernel";
  /// The policy's parameters given a value, by key; the others keep their defaults (under
  /// the linux profile; a preset's, the paper profile's). Set them with set().
  std::map<std::string, ParameterValue, std::less<>> parameters;

  /// Sets the host model's switch or the policy's parameter `key`. On a preset (wrench_cache),
  /// the policy it presets takes its place with the preset's values, so that the other
  /// parameters keep them. Throws ConfigError if neither has such a key, or if `value` is not
  /// of its kind or out of its bounds.
  void set(std::string_view key, ParameterValue value);
  /// The value of the host model's switch or the policy's parameter `key` (given, or its
  /// default). Throws ConfigError if neither has such a key.
  ParameterValue value(std::string_view key) const;
  /// value(key) of a switch; throws ConfigError if `key` is not one.
  bool get(std::string_view key) const;
  /// value(key) of an integer or a size; throws ConfigError if `key` is neither.
  std::int64_t integer(std::string_view key) const;
  /// value(key) of a ratio; throws ConfigError if `key` is not one.
  double ratio(std::string_view key) const;

  /// The paper's model as WRENCH-cache implements it: dirty ratio 0.4, 5 s interval, 30 s
  /// expiry, and WRENCH-cache's reading of the paper where the paper is ambiguous.
  static CacheSettings paper() {
    CacheSettings s;
    s.policy = "wrench_cache";
    s.dirty_ratio = 0.4;
    s.dirty_background_ratio = 0.1;
    s.dirty_expire = 30.0;
    s.writeback_interval = 5.0;
    s.copies_hold_cores = s.large_folios = s.numa_nodes = false;
    return s;
  }
  /// The kernel's behaviour with its default knobs.
  static CacheSettings kernel() { return CacheSettings{}; }
};

}  // namespace pagecache
