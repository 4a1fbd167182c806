#pragma once
// ReportActivity: the consumer of a run's events (trace.hpp) that report.html draws as its
// activity chart: bytes written back by cause, bytes evicted, and seconds writers were held by
// dirty throttling, summed over hosts, per time bucket. Memory stays bounded whatever the
// run's length: buckets start 1 ms wide, and when an event falls past the last of the 512,
// neighbours are merged in pairs and the width doubled (sums are kept exactly).

#include <pagecache/trace.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pagecache::report {

class ReportActivity final : public TraceSink {
 public:
  static constexpr std::size_t kMaxBuckets = 512;
  static constexpr double kFirstWidth = 1e-3;  ///< seconds
  static constexpr std::size_t kCauses = 5;    ///< FlushCause's values

  /// One bucket: [index * width(), (index + 1) * width()).
  struct Bucket {
    std::array<std::int64_t, kCauses> flushed{};  ///< by FlushCause
    std::int64_t evicted = 0;
    double throttled = 0.0;  ///< seconds of pauses within the bucket, summed over writers
  };

  bool wants_flows() const override { return false; }
  void on_flush(const FlushEvent& e) override;
  void on_eviction(const EvictionEvent& e) override;
  void on_throttle(const ThrottleEvent& e) override;
  void on_end(double time) override;

  /// Seconds each bucket spans.
  double width() const noexcept { return width_; }
  /// From time 0 up to the bucket of the last event or of the run's end, at most kMaxBuckets.
  const std::vector<Bucket>& buckets() const noexcept { return buckets_; }
  /// When the run ended (on_end), else the latest time reported.
  double end() const noexcept { return end_; }
  /// Whether anything was reported at all (a run with no consumer attached reports nothing).
  bool recorded() const noexcept { return recorded_; }

 private:
  // The bucket holding time `t`, made (merging pairs as needed) if it is past the last.
  Bucket& at(double t);
  std::size_t index(double t) const noexcept;
  void merge_pairs();

  double width_ = kFirstWidth;
  // The bucket index() found last, and the times it surely holds (empty: none).
  struct Hint {
    double lo = 0.0;
    double hi = 0.0;
    std::size_t index = 0;
  };
  mutable Hint hint_;
  std::vector<Bucket> buckets_;
  double end_ = 0.0;
  bool recorded_ = false;
};

}  // namespace pagecache::report
