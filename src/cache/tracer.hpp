#pragma once
// Tracer: where a host's page cache, flusher and I/O controller report flushes, evictions and
// throttling pauses (pagecache/trace.hpp). One per host, shared by the three; without a
// consumer each report is one test of a null pointer.

#include <pagecache/simulator.hpp>
#include <pagecache/trace.hpp>

#include <cstdint>

namespace pagecache::cache {

struct Tracer {
  TraceSink* sink = nullptr;
  const Simulator* sim = nullptr;
  std::uint32_t host = 0;

  void flush(FlushCause cause, std::int64_t bytes) const {
    if (sink != nullptr && bytes > 0) [[unlikely]] sink->on_flush({.host = host, .time = sim->now(), .cause = cause, .bytes = bytes});
  }
  void eviction(std::int64_t bytes) const {
    if (sink != nullptr && bytes > 0) [[unlikely]] sink->on_eviction({.host = host, .time = sim->now(), .bytes = bytes});
  }
  void throttle(double start) const {
    if (sink != nullptr) [[unlikely]] sink->on_throttle({.host = host, .start = start, .end = sim->now()});
  }
};

}  // namespace pagecache::cache
