#pragma once
// A device's own write cache (an SSD's SLC cache, a RAID controller's, a virtual machine's
// host's): a burst rate until it fills, a sustained rate after. Measured by O_DIRECT writes of
// random data in pieces, each timed, until the rate has fallen and settled or a bound (time,
// space) is hit; the fall is told from the pieces' noise by its depth and its length.

#include "calibrate/measure.hpp"
#include "calibrate/scratch.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pagecache::calibrate {

/// A fall: this many pieces in a row under this fraction of the median rate before them.
inline constexpr double kFallRatio = 0.7;
inline constexpr std::size_t kFallPieces = 4;
/// Settled after a fall: the last kFallPieces pieces within this fraction of their median.
inline constexpr double kSettledWithin = 0.10;

struct WriteCacheFinding {
  bool fell = false;
  std::size_t fall = 0;          ///< the first piece after the cache filled
  std::int64_t cache_bytes = 0;  ///< bytes written before it
  double burst = 0.0;            ///< median rate before it (of every piece, without a fall)
  double sustained = 0.0;        ///< median rate from it on
  double spread_pct = 0.0;       ///< (max - min) / median of those pieces (of every piece, without a fall)
};

/// Where the pieces' rate fell, if it did: the first piece from which kFallPieces in a row, and
/// the median of all from it on, are under kFallRatio of the median of those before it.
WriteCacheFinding find_write_cache(const std::vector<Rate>& pieces);

/// Whether to stop: the rate has fallen and its last kFallPieces pieces agree within kSettledWithin.
bool write_rate_settled(const std::vector<Rate>& pieces);

struct WriteCacheSetting {
  std::int64_t piece = 256LL << 20;
  std::int64_t request = 16LL << 20;
  std::int64_t most = 64LL << 30;  ///< bytes, also never over half the file system's free space
  double seconds = 60.0;
  bool quick = false;  ///< a short run: its figures a comment, never platform keys
};

struct WriteCache {
  bool measured = false;
  std::string why;  ///< not measured: why
  WriteCacheSetting setting;
  std::int64_t free_before = 0;  ///< the file system's free bytes when it began
  std::vector<Rate> pieces;
  std::string stopped;  ///< what ended it
  WriteCacheFinding finding;
};

/// Measures it in `scratch` (on the file system of `dir`) and removes its file.
WriteCache measure_write_cache(const std::filesystem::path& dir, const Scratch& scratch, const WriteCacheSetting& setting);

/// The platform's `write_cache` and `sustained_write_bw` lines, or a comment saying why not:
/// also not when the sustained rate is above `write_bw` (writeback's), which never slows then.
/// write_cache is what pcsim's cache must hold for the fall to come where it came: the bytes
/// before it less what the medium drained meanwhile, x (1 - sustained / burst).
std::string write_cache_toml(const WriteCache& w, double write_bw);

}  // namespace pagecache::calibrate
