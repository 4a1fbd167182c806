// IoController: reads of parts of a file (access patterns), request by request.

#include "cache/chunk_read.hpp"
#include "cache/io_controller.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

Task<IoResult> IoController::read_ranges(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group) {
  const FileInfo& info = (*files_)[file];
  if (buffer <= 0) throw ConfigError(fmt::format("'{}': a read's buffer must be > 0 bytes, got {}", info.name, buffer));
  if (info.is_remote()) throw ConfigError(fmt::format("'{}': reads of parts of a file are of local files only", info.name));
  return read_ranges_of(file, std::move(next), buffer, group);
}

Task<IoResult> IoController::read_ranges_of(FileId file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupId group) {
  const double start = sim_->now();
  const FileInfo& info = (*files_)[file];
  const std::int64_t size = info.size;
  const Disk* const disk = info.disk;
  co_await take_buffer(buffer, group, file, "reading");
  cache_->track_ranges(file);
  IoResult result{.start = start};
  for (ByteRange r; next(r);) {
    if (r.offset < 0 || r.length <= 0 || r.offset > size - r.length) {
      throw SimulationError(fmt::format("'{}' ({} bytes): a read of {} bytes at offset {} is not within the file", info.name, size, r.length,
                                        r.offset));
    }
    ++chunks_;
    // The pages the request touches (the file's last page ends with the file).
    const std::int64_t first = r.offset / kPageSize * kPageSize;
    const std::int64_t end = std::min(size, (r.offset + r.length + kPageSize - 1) / kPageSize * kPageSize);
    const ReadRequest request{.file = file, .file_size = size, .bytes = end - first, .anonymous = 0, .offset = first};
    std::int64_t disk_read = group == kRootGroup ? evict_for_chunk(*cache_, request) : -1;
    if (disk_read < 0) disk_read = co_await room_for_chunk(file, size, request.bytes, 0, first, group, "reading");
    const std::int64_t cold = cold_taken();
    start_chunk(*cache_, request, disk_read, {}, group, sim_->now());
    // One device request for the pages missing (into new cache pages), then the copy of the
    // cached part into the buffer, which is warm after the first request.
    const std::int64_t copied = std::max<std::int64_t>(r.length - disk_read, 0);
    if (disk_read > 0) {
      const double cold_share = disk_read > 0 ? static_cast<double>(cold_taken() - cold) / static_cast<double>(disk_read) : 0.0;
      co_await disk->read(disk_read, memory_->fresh_copy_rate(cold_share), disk_read);
    }
    if (copied > 0) co_await memory_->read(copied);
    result.bytes += r.length;
    result.cache_bytes += copied;
    result.disk_bytes += disk_read;
  }
  cache_->release_anonymous(buffer, group);
  result.end = sim_->now();
  co_return result;
}

}  // namespace pagecache::cache
