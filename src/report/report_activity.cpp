#include "report/report_activity.hpp"

#include <algorithm>
#include <cmath>

namespace pagecache::report {

std::size_t ReportActivity::index(double t) const noexcept {
  // Most events fall in the bucket of the one before: inside it, 10^-9 of a width from its
  // edges (where rounding could put t / width on either side), the quotient's floor is that
  // bucket's index, and no division is needed (a throttled run reports millions of events).
  if (t >= hint_.lo && t < hint_.hi) return hint_.index;
  const double i = std::floor(std::max(t, 0.0) / width_);
  if (i < static_cast<double>(kMaxBuckets)) {
    const double edge = width_ * 1e-9;
    hint_ = {i * width_ + edge, (i + 1.0) * width_ - edge, static_cast<std::size_t>(i)};
  }
  // Far past any run (10^10 s at most): capped, so the cast is defined; merging brings it in.
  return static_cast<std::size_t>(std::min(i, 1e15));
}

void ReportActivity::merge_pairs() {
  for (std::size_t i = 0; i < buckets_.size(); i += 2) {
    Bucket merged = buckets_[i];
    if (i + 1 < buckets_.size()) {
      const Bucket& next = buckets_[i + 1];
      for (std::size_t c = 0; c < kCauses; ++c) merged.flushed[c] += next.flushed[c];
      merged.evicted += next.evicted;
      merged.throttled += next.throttled;
    }
    buckets_[i / 2] = merged;  // i / 2 <= i: written after every bucket it merges was read
  }
  buckets_.resize((buckets_.size() + 1) / 2);
  width_ *= 2.0;
  hint_ = {};
}

ReportActivity::Bucket& ReportActivity::at(double t) {
  recorded_ = true;
  end_ = std::max(end_, t);
  while (index(t) >= kMaxBuckets) merge_pairs();
  const std::size_t i = index(t);
  if (i >= buckets_.size()) buckets_.resize(i + 1);
  return buckets_[i];
}

void ReportActivity::on_flush(const FlushEvent& e) { at(e.time).flushed[static_cast<std::size_t>(e.cause)] += e.bytes; }

void ReportActivity::on_eviction(const EvictionEvent& e) { at(e.time).evicted += e.bytes; }

void ReportActivity::on_throttle(const ThrottleEvent& e) {
  at(e.end);  // first: the buckets it spans are then final
  const double start = std::min(std::max(e.start, 0.0), e.end);
  for (std::size_t i = index(start); i <= index(e.end) && i < buckets_.size(); ++i) {
    const double lo = std::max(start, static_cast<double>(i) * width_);
    const double hi = std::min(e.end, static_cast<double>(i + 1) * width_);
    if (hi > lo) buckets_[i].throttled += hi - lo;
  }
}

void ReportActivity::on_end(double time) { at(time); }

}  // namespace pagecache::report
