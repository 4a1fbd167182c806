#pragma once
// The benchmarks' random numbers: splitmix64 (Steele, Lea and Flood, 2014), the same sequence
// on every machine, so that two builds are timed on the same requests.

#include <cstdint>

namespace pagecache::bench {

/// The next number of the sequence `state` is at.
inline std::uint64_t splitmix64(std::uint64_t& state) noexcept {
  state += 0x9E3779B97F4A7C15ull;
  std::uint64_t z = state;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace pagecache::bench
