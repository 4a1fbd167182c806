#pragma once
// RequestPattern: how a task reads one file by parts — in order, at random, strided, or a list
// of ranges — and RequestStream, the requests it makes, one at a time, for Host::read_ranges.
// Random orders are a seeded function of the pattern alone (a Feistel permutation of the
// request slots, cycle-walked to their count; draws with replacement from SplitMix64, the
// generator of file-set orders too), so a
// stream costs O(1) memory whatever the file's size and gives the same requests on any
// compiler and machine.

#include "workload/sample_order.hpp"

#include <pagecache/host.hpp>

#include <cstdint>
#include <vector>

namespace pagecache::workload {

struct RequestPattern {
  enum class Kind : std::uint8_t { Sequential, Random, Strided, Ranges };
  Kind kind = Kind::Sequential;
  /// The region read: [offset, offset + length) (Ranges: unused).
  std::int64_t offset = 0;
  std::int64_t length = 0;
  /// Bytes per request (> 0). The region is cut into slots of this size from its start, the
  /// last one shorter.
  std::int64_t request = 0;
  /// Strided: bytes from one request's start to the next's (>= request).
  std::int64_t stride = 0;
  /// Requests per epoch; 0: every slot once (Random, Sequential, Strided: as many as fit).
  /// Random: the slots are fewer than 2^32.
  std::int64_t count = 0;
  /// Random: draws with replacement (a slot may come twice in an epoch), else each at most once.
  bool replacement = false;
  std::uint64_t seed = 0;
  /// Ranges: each read in requests of `request` bytes (0: as one request), in this order.
  std::vector<ByteRange> ranges = {};
};

/// The requests of `pattern`, epoch by epoch (a pass over it; random epochs each in an order
/// of their own). The pattern must be valid (the loader checks it).
class RequestStream {
 public:
  explicit RequestStream(RequestPattern pattern);
  /// Starts epoch `epoch` (0, 1, ...): next() gives its requests from the first.
  void start_epoch(std::int64_t epoch);
  /// The epoch's next request, or false when it is done.
  bool next(ByteRange& out);
  /// Requests per epoch.
  std::int64_t per_epoch() const noexcept { return per_epoch_; }

 private:
  /// Slot `i` of the region as a request.
  ByteRange slot(std::int64_t i) const noexcept;
  /// Request `i` of the current epoch.
  ByteRange request(std::int64_t i);

  RequestPattern pattern_;
  std::int64_t slots_ = 0;      // Random, Sequential: slots of the region
  std::int64_t per_epoch_ = 0;
  std::int64_t index_ = 0;      // next request of the epoch
  SplitMix64 draws_{0};         // draws with replacement
  std::uint64_t key_ = 0;       // this epoch's permutation key
  int half_bits_ = 0;           // the permutation's domain is 2^(2 * half_bits_)
  std::size_t range_ = 0;       // Ranges: the range being read and where in it
  std::int64_t within_ = 0;
};

/// A permutation of [0, n) chosen by `key`: a 4-round Feistel network on the smallest even
/// number of bits that holds n, walked until it lands below n (less than 4 steps expected).
std::uint64_t permute(std::uint64_t index, std::uint64_t n, std::uint64_t key, int half_bits) noexcept;
/// Half the bits of permute's domain for n items.
int permutation_half_bits(std::uint64_t n) noexcept;

}  // namespace pagecache::workload
