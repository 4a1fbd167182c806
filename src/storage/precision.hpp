#pragma once
// The one place for numeric tolerances of the storage layer.

namespace pagecache::precision {

/// Relative tolerance when comparing rates and fair-share levels: two levels closer than this
/// are the same level (ties are not broken by rounding noise).
inline constexpr double kRelativeRate = 1e-12;

/// Work (bytes, core-seconds) below which a flow counts as finished. Bytes are whole numbers,
/// so a millionth of a byte is rounding noise.
inline constexpr double kWork = 1e-6;

}  // namespace pagecache::precision
