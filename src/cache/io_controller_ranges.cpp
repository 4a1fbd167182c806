// IoController: reads of parts of a file (access patterns), request by request.

#include "cache/chunk_read.hpp"
#include "cache/io_controller.hpp"
#include "cache/range_readahead.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

namespace {

// The pages a request touches (the file's last page ends with the file).
ByteRange pages_of(const ByteRange& r, std::int64_t size) noexcept {
  const std::int64_t first = r.offset / kPageSize * kPageSize;
  return {.offset = first, .length = std::min(size, (r.offset + r.length + kPageSize - 1) / kPageSize * kPageSize) - first};
}

void check_within(const FileInfo& info, const ByteRange& r, const char* verb) {
  if (r.offset < 0 || r.length <= 0 || r.offset > info.size - r.length) {
    throw SimulationError(fmt::format("'{}' ({} bytes): a {} of {} bytes at offset {} is not within the file", info.name, info.size, verb, r.length,
                                      r.offset));
  }
}

// The requests' own time is slept in stretches of this much: a thread's system calls, one
// after the other, add up the same; a stretch is one event where 10^7 requests would be 10^7.
constexpr double kRequestTimeBatch = 1e-3;

}  // namespace

Task<IoResult> IoController::read_ranges(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group, ReadAdvice advice,
                                         bool direct, NodeId node) {
  const FileInfo& info = (*files_)[file];
  if (buffer <= 0) throw ConfigError(fmt::format("'{}': a read's buffer must be > 0 bytes, got {}", info.name, buffer));
  if (info.is_remote()) throw ConfigError(fmt::format("'{}': reads of parts of a file are of local files only", info.name));
  if (direct) return ranges_direct(file, std::move(next), buffer, group, false, node);
  return read_ranges_of(file, std::move(next), buffer, group, advice, node);
}

Task<IoResult> IoController::ranges_direct(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group, bool writing,
                                           NodeId node) {
  const double start = sim_->now();
  const FileInfo& info = (*files_)[file];
  const Disk* const disk = info.disk;
  // The application's buffer is the only memory it takes; a write's comes from it.
  co_await take_buffer(buffer, group, file, writing ? "writing" : "reading", node);
  if (writing) cache_->track_ranges(file);
  IoResult result{.start = start};
  double pending = 0.0;  // request time not yet slept
  for (ByteRange r; next(r);) {
    check_within(info, r, writing ? "write" : "read");
    ++chunks_;
    pending += request_time_;
    if (pending >= kRequestTimeBatch) {
      co_await sim_->sleep(pending);
      pending = 0.0;
    }
    // One request at a time, DMA to or from the buffer: the device's request rate bounds it.
    if (writing) {
      co_await disk->write(r.length, r.length);
      // What the page cache held of those pages is stale: dropped (invalidate_inode_pages2_range).
      cache_->drop_clean_range(file, pages_of(r, info.size).offset, pages_of(r, info.size).length);
    } else {
      co_await disk->read(r.length, kUnbounded, r.length);
    }
    result.bytes += r.length;
    result.disk_bytes += r.length;
  }
  if (pending > 0.0) co_await sim_->sleep(pending);
  cache_->touch_from(node);
  cache_->release_anonymous(buffer, group);
  result.end = sim_->now();
  co_return result;
}

Task<IoResult> IoController::read_ranges_of(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group,
                                            ReadAdvice advice, NodeId node) {
  const double start = sim_->now();
  const FileInfo& info = (*files_)[file];
  const std::int64_t size = info.size;
  const Disk* const disk = info.disk;
  co_await take_buffer(buffer, group, file, "reading", node);
  cache_->track_ranges(file);
  RangeReadahead readahead(*disk, advice);
  IoResult result{.start = start};
  std::int64_t fetched = 0;  // read by the device beyond the requests so far, not yet found by one
  double pending = 0.0;      // request time not yet slept
  for (ByteRange r; next(r);) {
    check_within(info, r, "read");
    ++chunks_;
    pending += request_time_;
    if (pending >= kRequestTimeBatch) {
      co_await sim_->sleep(pending);
      pending = 0.0;
    }
    const ByteRange pages = pages_of(r, size);
    // Room for what the device reads: the request's holes, and a readahead window's.
    const ByteRange window = readahead.window(pages, size);
    const ReadRequest request{.file = file, .file_size = size, .bytes = window.length, .anonymous = 0, .offset = window.offset};
    std::int64_t disk_read = group == kRootGroup ? evict_for_chunk(*cache_, request) : -1;
    if (disk_read < 0) disk_read = co_await room_for_chunk(file, size, request.bytes, 0, request.offset, group, "reading");
    const std::int64_t cold = cold_taken();
    const RemoteTally before = cache_->nodes().remote();
    // The request's pages are read (the cached ones touched); the rest of the window only fills.
    cache_->touch_from(node);
    cache_->charge_file(file, group);
    const std::int64_t missed = cache_->read_range(file, pages.offset, pages.length, sim_->now());
    const std::int64_t ahead = cache_->read_ahead(file, pages.offset + pages.length, window.length - pages.length, sim_->now());
    PC_ASSERT(missed + ahead == disk_read);
    // One device request for what was missing (into new cache pages), then the copy of the
    // cached part of the request into the buffer, which is warm after the first request.
    const std::int64_t copied = std::max<std::int64_t>(r.length - missed, 0);
    if (disk_read > 0) {
      const double cold_share = static_cast<double>(cold_taken() - cold) / static_cast<double>(disk_read);
      const RemoteShare placed{.source = share(cache_->nodes().remote().cache - before.cache, disk_read), .destination = 0.0};
      co_await disk->read(disk_read, memory(node).fresh_copy_rate(cold_share, placed), disk_read);
    }
    if (copied > 0) co_await memory(node).read(copied, RemoteShare{.source = share(cache_->nodes().remote().reread - before.reread, copied)});
    // The request's bytes, each once (timeline.csv adds them up): from the device as far as it
    // read the request's pages; of the rest, found cached, what the device read earlier in this
    // phase beyond earlier requests (a partial page's rest, a readahead window) is the device's
    // too, taken in order; the others were in the cache before.
    const std::int64_t from_request = std::min(r.length, missed);
    fetched += disk_read - from_request;
    const std::int64_t found = r.length - from_request;
    const std::int64_t from_fetched = std::min(found, fetched);
    fetched -= from_fetched;
    result.bytes += r.length;
    result.cache_bytes += found - from_fetched;
    result.disk_bytes += from_request + from_fetched;
  }
  if (pending > 0.0) co_await sim_->sleep(pending);
  cache_->touch_from(node);
  cache_->release_anonymous(buffer, group);
  result.end = sim_->now();
  co_return result;
}

Task<IoResult> IoController::write_ranges(FileId file, std::function<bool(ByteRange&)> next, GroupId group, bool direct, NodeId node) {
  const FileInfo& info = (*files_)[file];
  if (info.is_remote()) throw ConfigError(fmt::format("'{}': writes of parts of a file are of local files only", info.name));
  if (direct) return ranges_direct(file, std::move(next), kPageSize, group, true, node);
  return write_ranges_of(file, std::move(next), group, node);
}

Task<IoResult> IoController::write_ranges_of(FileId file, std::function<bool(ByteRange&)> next, GroupId group, NodeId node) {
  const double start = sim_->now();
  const FileInfo& info = (*files_)[file];
  cache_->charge_file(file, group);
  cache_->track_ranges(file);
  cache_->set_being_written(file, true);
  IoResult result{.start = start};
  double pending = 0.0;  // request time not yet slept
  for (ByteRange r; next(r);) {
    check_within(info, r, "write");
    ++chunks_;
    pending += request_time_;
    if (pending >= kRequestTimeBatch) {
      co_await sim_->sleep(pending);
      pending = 0.0;
    }
    // A write of part of a page copies and dirties the page (the kernel would read it first
    // if it is not cached: not modelled).
    const ByteRange pages = pages_of(r, info.size);
    const IoTally t = co_await write_chunk(file, pages.length, pages.offset, node);
    // The request's bytes, each once: what of its pages went to the device (written through),
    // the rest into the cache.
    const std::int64_t to_disk = std::min(r.length, t.disk_bytes);
    result.bytes += r.length;
    result.cache_bytes += r.length - to_disk;
    result.disk_bytes += to_disk;
  }
  if (pending > 0.0) co_await sim_->sleep(pending);
  cache_->set_being_written(file, false);
  result.end = sim_->now();
  co_return result;
}

void IoController::will_need(FileId file, ByteRange range) {
  const FileInfo& info = (*files_)[file];
  if (info.is_remote()) throw ConfigError(fmt::format("'{}': advice on parts of a file is for local files only", info.name));
  check_within(info, range, "prefetch");
  sim_->spawn(prefetch(file, pages_of(range, info.size)));
}

Task<void> IoController::prefetch(FileId file, ByteRange range) {
  const FileInfo& info = (*files_)[file];
  cache_->track_ranges(file);
  const ReadRequest request{.file = file, .file_size = info.size, .bytes = range.length, .anonymous = 0, .offset = range.offset};
  std::int64_t disk_read = evict_for_chunk(*cache_, request);
  if (disk_read < 0) disk_read = co_await room_for_chunk(file, info.size, request.bytes, 0, request.offset, kRootGroup, "prefetching");
  const std::int64_t cold = cold_taken();
  cache_->touch_from(0);  // the kernel's readahead worker: node 0
  const std::int64_t added = cache_->read_ahead(file, range.offset, range.length, sim_->now());
  PC_ASSERT(added == disk_read);
  if (added > 0) {
    const double cold_share = static_cast<double>(cold_taken() - cold) / static_cast<double>(added);
    co_await info.disk->read(added, memory(0).fresh_copy_rate(cold_share), added);
  }
}

std::int64_t IoController::dont_need(FileId file, ByteRange range) {
  const FileInfo& info = (*files_)[file];
  if (info.is_remote()) throw ConfigError(fmt::format("'{}': advice on parts of a file is for local files only", info.name));
  check_within(info, range, "drop");
  cache_->track_ranges(file);
  const ByteRange pages = pages_of(range, info.size);
  return cache_->drop_clean_range(file, pages.offset, pages.length);
}

}  // namespace pagecache::cache
