#pragma once
// SampleOrder: the files an access reads in each epoch, drawn by a generator of our own so that a
// seed gives the same orders on every compiler and standard library (std::shuffle and
// std::uniform_int_distribution are implementation-defined). SplitMix64 (Steele, Lea and Flood,
// 2014) for the bits, Lemire's multiply-and-reject for an unbiased draw below a bound (2019),
// Fisher-Yates (Durstenfeld's form, one step per file read) for a shuffle.

#include <cstdint>
#include <vector>

namespace pagecache::workload {

/// SplitMix64: 64 bits of state, every seed a full-period stream.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  std::uint64_t next() noexcept { return mix(state_ += 0x9e3779b97f4a7c15ULL); }
  /// SplitMix64's finaliser: a bijection of 64-bit words that mixes every bit into every other
  /// (the round function of RequestStream's permutations).
  static constexpr std::uint64_t mix(std::uint64_t z) noexcept {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// A uniform draw in [0, bound), bound >= 1: exact, with no modulo bias.
  std::uint32_t below(std::uint32_t bound) noexcept;

 private:
  std::uint64_t state_;
};

/// The files (indices in [0, files)) one access visits, epoch after epoch.
class SampleOrder {
 public:
  enum class Kind {
    InOrder,          ///< 0, 1, 2, ... every epoch
    Shuffled,         ///< a fresh uniform permutation each epoch, drawn as it is read
    WithReplacement,  ///< independent uniform draws
  };
  /// 1 <= files < 2^32. The same arguments give the same sequence of epochs.
  SampleOrder(std::uint64_t files, Kind kind, std::uint64_t seed);

  /// Starts an epoch: next() gives its files from the first.
  void start_epoch();
  /// The epoch's next file. InOrder and Shuffled: at most `files` per epoch (each once).
  std::uint32_t next();

 private:
  std::uint32_t files_;
  Kind kind_;
  SplitMix64 bits_;
  std::uint32_t position_ = 0;        // reads so far this epoch
  std::vector<std::uint32_t> order_;  // Shuffled: the permutation, drawn up to position_
};

}  // namespace pagecache::workload
