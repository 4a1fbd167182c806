#include "workload/sample_order.hpp"

#include <pagecache/error.hpp>

#include <numeric>
#include <utility>

namespace pagecache::workload {

// Lemire, "Fast random integer generation in an interval" (ACM TOMACS 2019): the high half of
// a 32 x 32-bit product, redrawn when the low half falls in the biased sliver.
std::uint32_t SplitMix64::below(std::uint32_t bound) noexcept {
  auto draw = [this] { return static_cast<std::uint32_t>(next() >> 32); };
  std::uint64_t m = static_cast<std::uint64_t>(draw()) * bound;
  auto low = static_cast<std::uint32_t>(m);
  if (low < bound) {
    const std::uint32_t threshold = static_cast<std::uint32_t>(-bound) % bound;  // 2^32 mod bound
    while (low < threshold) {
      m = static_cast<std::uint64_t>(draw()) * bound;
      low = static_cast<std::uint32_t>(m);
    }
  }
  return static_cast<std::uint32_t>(m >> 32);
}

SampleOrder::SampleOrder(std::uint64_t files, Kind kind, std::uint64_t seed)
    : files_(static_cast<std::uint32_t>(files)), kind_(kind), bits_(seed) {
  if (files == 0 || files > UINT32_MAX) throw ConfigError("a sample order needs between 1 and 2^32 - 1 files");
}

void SampleOrder::start_epoch() {
  position_ = 0;
  // A fresh permutation from the identity each epoch: an epoch's order depends on the seed and
  // the draws before it only.
  if (kind_ == Kind::Shuffled) {
    order_.resize(files_);
    std::iota(order_.begin(), order_.end(), 0U);
  }
}

std::uint32_t SampleOrder::next() {
  switch (kind_) {
    case Kind::WithReplacement:
      return bits_.below(files_);
    case Kind::InOrder:
      if (position_ >= files_) throw SimulationError("an access read more files in one epoch than its set has");
      return position_++;
    case Kind::Shuffled: {
      if (position_ >= files_) throw SimulationError("an access read more files in one epoch than its set has");
      const std::uint32_t i = position_++;
      std::swap(order_[i], order_[i + bits_.below(files_ - i)]);  // Fisher-Yates, one step
      return order_[i];
    }
  }
  return 0;
}

}  // namespace pagecache::workload
