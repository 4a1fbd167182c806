// IoController: writes (Algorithm 3 and what the linux profile adds to it): a file's write in
// chunks, dirty throttling, the copy into the cache, writethrough.

#include "cache/io_controller.hpp"

#include "cache/chunk_read.hpp"

#include "engine/check.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

// Not a coroutine: it hands out the task that writes the chunk, a frame fewer per chunk.
Task<IoTally> IoController::write_chunk(FileId file, std::int64_t chunk, std::int64_t at, NodeId node) {
  if ((*files_)[file].is_remote()) return write_chunk_remote(file, chunk);
  if (cache_->settings().write_mode == WriteMode::Writethrough) return write_chunk_writethrough(file, chunk, at, node);
  return write_chunk_writeback(file, chunk, at, node);
}

Task<IoTally> IoController::write_chunk_remote(FileId file, std::int64_t chunk) {
  // No client write cache (the paper's NFS setting): every write goes to the server.
  const FileInfo& info = (*files_)[file];
  co_await info.remote.server->serve_write(info.remote.server_file, chunk, *info.remote.route);
  co_return IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
}

Task<std::int64_t> IoController::write_to_cache(FileId file, std::int64_t bytes, std::int64_t reclaimed, std::int64_t at, NodeId node) {
  // The pages are taken now and hold the data once the copy is done: the dirty block's entry
  // time is the end of the copy. The file's group is charged for them.
  if (const GroupId group = cache_->groups().of(file); group != kRootGroup) {
    const std::int64_t evicted = cache_->totals().evicted;
    co_await make_group_room(group, bytes, file, "writing");
    reclaimed += cache_->totals().evicted - evicted;
    bytes = std::min(bytes, cache_->free());  // others may have taken memory meanwhile
    if (bytes == 0) co_return 0;
  }
  const std::int64_t cold = cold_taken();
  const std::int64_t reserved = cache_->nodes().remote().reserved;
  cache_->touch_from(node);
  cache_->reserve(bytes);
  co_await memory(node).write(bytes, std::min(reclaimed, bytes), cold_taken() - cold,
                              numa_ ? remote_since(&RemoteTally::reserved, reserved, bytes) : RemoteShare{});
  cache_->touch_from(node);
  commit_write(file, at, bytes);
  flusher_->notify_dirty(cache_->groups().of(file));
  co_return bytes;
}

// The whole file is written here, chunk after chunk, rather than a coroutine per chunk: with
// many writers each chunk would otherwise create a frame and resume two, all out of cache.
// What is decided between two suspensions is decided by the writer's DirtyThrottle::Writer, so
// that the frame holds little more than it.
void IoController::commit_write(FileId file, std::int64_t at, std::int64_t bytes) {
  cache_->commit_dirty(file, bytes, sim_->now(), at);  // kWholeFile is kNoOffset
}

Task<IoResult> IoController::write_file_throttled(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool whole_file, std::int64_t at,
                                                  NodeId node) {
  const double start = sim_->now();
  if (whole_file) cache_->set_being_written(file, true);
  const double device_bw = (*files_)[file].disk->write_bandwidth();
  const GroupId group = cache_->groups().of(file);
  for (std::int64_t offset = 0; offset < bytes; offset += chunk_size) {
    std::int64_t remaining = std::min(chunk_size, bytes - offset);
    DirtyThrottle::Writer writer(throttle_, device_bw, group);
    while (remaining > 0) {
      // What is evicted from here to the copy frees the pages the copy fills.
      std::int64_t evicted = cache_->totals().evicted;
      const std::int64_t cold = cold_taken();
      const std::int64_t reserved = cache_->nodes().remote().reserved;
      cache_->touch_from(node);  // the step's pages are reserved on the writer's node first
      const DirtyThrottle::Step step = writer.next(remaining);
      if (step.kind == DirtyThrottle::Step::Pause) {
        co_await sim_->sleep(step.pause);
        cache_->listeners().tracer.throttle(sim_->now() - step.pause);
        writer.paused(step);
      } else if (step.kind == DirtyThrottle::Step::MakeRoom) {
        // Out of memory with nothing clean to reclaim: dirty data must be written first, as
        // reclaim does (pageout), or copies and writebacks in flight must land.
        if (co_await write_back(remaining - cache_->free(), kNoFile, FlushCause::Reclaim) == 0) {
          check_writer_can_wait(file, remaining);
          co_await wait_for_progress();
        }
      } else {
        if (group != kRootGroup) co_await make_group_room(group, step.to_cache, file, "writing");
        evicted = cache_->totals().evicted - evicted;
        co_await memory(node).write(step.to_cache, std::min(evicted, step.to_cache), cold_taken() - cold,
                                    numa_ ? remote_since(&RemoteTally::reserved, reserved, step.to_cache) : RemoteShare{});
        cache_->touch_from(node);
        commit_write(file, at == ReadRequest::kWholeFile ? at : at + offset + std::min(chunk_size, bytes - offset) - remaining, step.to_cache);
        flusher_->notify_dirty(group);
        remaining -= step.to_cache;
      }
    }
  }
  if (whole_file) cache_->set_being_written(file, false);
  co_return file_result(start, sim_->now(), IoTally{.bytes = bytes, .cache_bytes = bytes, .disk_bytes = 0});
}

Task<IoTally> IoController::write_chunk_writeback(FileId file, std::int64_t chunk, std::int64_t at, NodeId node) {
  if (throttles_writers()) {
    const IoResult r = co_await write_file_throttled(file, chunk, chunk, false, at, node);
    co_return IoTally{.bytes = r.bytes, .cache_bytes = r.cache_bytes, .disk_bytes = r.disk_bytes};
  }
  std::int64_t to_memory = 0;
  if (const WriteStart start = plan_write_start(*cache_, chunk); start.under_threshold) {
    const std::int64_t evicted = cache_->evict(start.evict, file);
    to_memory = plan_write_start(*cache_, chunk).to_cache;  // as memory is after the eviction
    if (to_memory > 0) to_memory = co_await write_to_cache(file, to_memory, evicted, at, node);
  }
  std::int64_t remaining = chunk - to_memory;
  while (remaining > 0) {
    // Planned again after the writeback (others ran meanwhile) and after the eviction.
    const std::int64_t flushed = co_await write_back(plan_write_step(*cache_, remaining).flush, kNoFile, FlushCause::DirtyLimit);
    const std::int64_t evicted = cache_->evict(plan_write_step(*cache_, remaining).evict, file);
    std::int64_t to_cache = plan_write_step(*cache_, remaining).to_cache;
    if (to_cache == 0 && flushed == 0 && evicted == 0) {
      // Nothing to flush or evict now: other writers' data may still be in flight.
      check_writer_can_wait(file, remaining);
      co_await wait_for_progress();
    }
    if (to_cache > 0) to_cache = co_await write_to_cache(file, to_cache, evicted, at == ReadRequest::kWholeFile ? at : at + chunk - remaining, node);
    remaining -= to_cache;
  }
  co_return IoTally{.bytes = chunk, .cache_bytes = chunk, .disk_bytes = 0};
}

Task<IoTally> IoController::write_chunk_writethrough(FileId file, std::int64_t chunk, std::int64_t at, NodeId node) {
  co_await (*files_)[file].disk->write(chunk);
  cache_->evict(chunk - cache_->free(), file);
  cache_->touch_from(node);
  // A range written through is cached clean, as if read: what was not cached of it, if it fits.
  if (at != ReadRequest::kWholeFile && chunk - cache_->ranges().cached_in(file, at, chunk) <= cache_->free()) cache_->read_range(file, at, chunk, sim_->now());
  else if (at == ReadRequest::kWholeFile) cache_->add_clean(file, std::min(chunk, cache_->free()), sim_->now());
  co_return IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
}

Task<IoResult> IoController::write_file(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  check_request(chunk_size);
  cache_->charge_file(file, group);
  const FileInfo& info = (*files_)[file];
  if (!direct && !info.is_remote() && cache_->settings().write_mode == WriteMode::Writeback && throttles_writers()) {
    chunks_ += static_cast<std::uint64_t>((bytes + chunk_size - 1) / chunk_size);
    // A file held by range is written in place, from its start.
    return write_file_throttled(file, bytes, chunk_size, true, cache_->ranges().tracked(file) ? 0 : ReadRequest::kWholeFile, node);
  }
  return write_file_in_chunks(file, bytes, chunk_size, direct, node);
}

Task<IoResult> IoController::write_file_in_chunks(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool direct, NodeId node) {
  const double start = sim_->now();
  IoTally total;
  cache_->set_being_written(file, true);
  // Over NFS there is no client write cache: O_DIRECT changes nothing, every write goes to the
  // server (write_chunk).
  const Disk* const direct_to = direct && !(*files_)[file].is_remote() ? (*files_)[file].disk : nullptr;
  const bool in_place = cache_->ranges().tracked(file);  // a file held by range is written in place
  for (std::int64_t offset = 0; offset < bytes; offset += chunk_size) {
    const std::int64_t chunk = std::min(chunk_size, bytes - offset);
    ++chunks_;
    if (direct_to == nullptr) {
      total += co_await write_chunk(file, chunk, in_place ? offset : ReadRequest::kWholeFile, node);
      continue;
    }
    co_await direct_to->write(chunk, chunk);  // O_DIRECT: straight to the disk, in requests of the chunk
    total += IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
  }
  cache_->set_being_written(file, false);
  co_return file_result(start, sim_->now(), total);
}

}  // namespace pagecache::cache
