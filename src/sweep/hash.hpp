#pragma once
// The one hash of the sweep layer: 64-bit FNV-1a, written as 16 hex digits. Stable across
// machines and builds (std::hash is not), so that ids and fingerprints written by one pcsim
// are recognised by another.

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace pagecache::sweep {

inline constexpr std::uint64_t kFnvStart = 0xcbf29ce484222325ULL;

inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = kFnvStart) {
  for (const unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

inline std::string hex16(std::uint64_t h) { return fmt::format("{:016x}", h); }

/// Whether `text` is 16 lower-case hex digits, as hex16 writes them.
inline bool is_hex16(std::string_view text) {
  if (text.size() != 16) return false;
  for (const char c : text)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

}  // namespace pagecache::sweep
