// The wrench_cache preset: the paper's model as WRENCH-cache implements it
// (docs/wrench-cache.md), where the paper leaves a decision open. It is the kernel policy with
// every switch at WRENCH-cache's decision (each one's paper default): fixed, no parameters of
// its own beyond the kernel knobs every policy reads (ratios, expiry, interval).

#include "cache/policy.hpp"

namespace pagecache::cache {

extern const PolicyRegistration kWrenchCachePreset{
    .declaration = {
        .name = "wrench_cache",
        .doc = "WRENCH-cache's reading of the paper (the paper profile): the kernel policy with every switch off",
        .parameters = {},
        .preset_of = "kernel",
    },
};

}  // namespace pagecache::cache
