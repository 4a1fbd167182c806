#include "cache/io_controller.hpp"

#include "cache/chunk_read.hpp"

#include "engine/check.hpp"
#include "storage/readahead.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::cache {

namespace {

// A whole file's read or write as Host reports it: its span and what it moved.
IoResult file_result(double start, double end, const IoTally& t) {
  return IoResult{.start = start, .end = end, .bytes = t.bytes, .cache_bytes = t.cache_bytes, .disk_bytes = t.disk_bytes};
}

}  // namespace

Task<std::int64_t> IoController::write_back(std::int64_t amount, FileId excluded, FlushCause cause, GroupId group) {
  if (amount <= 0) co_return 0;
  FlushScratch scratch = take_scratch();
  std::vector<PageCache::Flushed>& taken = scratch.parts;
  const std::int64_t total = cache_->flush(amount, excluded, taken, group);
  flushed_ += total;
  cache_->tracer().flush(cause, total);
  // The data may belong to files on different devices: one write per device, in the order
  // the data was taken.
  auto& writes = scratch.writes;
  for (const auto& part : taken) {
    const Disk* disk = (*files_)[part.file].disk;
    auto it = std::find_if(writes.begin(), writes.end(), [disk](const auto& w) { return w.first == disk; });
    if (it == writes.end()) writes.emplace_back(disk, part.bytes);
    else it->second += part.bytes;
  }
  for (const auto& [disk, bytes] : writes) co_await disk->write(bytes);
  for (const auto& part : taken) cache_->end_writeback(part);
  release_scratch(std::move(scratch));
  co_return total;
}

IoController::IoController(Simulator& sim, PageCache& cache, const Memory& memory, FileTable& files, Flusher& flusher)
    : sim_(&sim), cache_(&cache), memories_{&memory}, files_(&files), flusher_(&flusher), throttle_(sim, cache, flusher) {
  machine_at_rest();
  cache_->set_progress_hook([this] {
    if (progress_ && !progress_->triggered()) progress_->trigger();
  });
}

bool IoController::throttles_writers() const noexcept { return cache_->policy().throttles_writers(); }

void IoController::machine_at_rest() { throttle_.at_rest(); }

void IoController::report_free_pages(double delay, std::int64_t warm) {
  reporting_.emplace(cache_->free(), cache_->anonymous(), warm, delay, cache_->policy().large_folios());
  cache_->set_free_memory_hook([this](std::int64_t free, std::int64_t anonymous) { reporting_->observe(free, anonymous, sim_->now()); });
}

void IoController::cache_at_start(FileId file, std::int64_t bytes) {
  if (!reporting_) {
    cache_->add_clean(file, bytes, sim_->now());
    return;
  }
  // Cached before the run: its memory was neither freed nor taken by the run.
  cache_->set_free_memory_hook({});
  cache_->add_clean(file, bytes, sim_->now());
  reporting_->rebase(cache_->free(), cache_->anonymous());
  cache_->set_free_memory_hook([this](std::int64_t free, std::int64_t anonymous) { reporting_->observe(free, anonymous, sim_->now()); });
}

Task<void> IoController::wait_for_progress() {
  if (!progress_ || progress_->triggered()) progress_.emplace(*sim_);
  co_await progress_->wait();
}

void IoController::check_writer_can_wait(FileId file, std::int64_t bytes) const {
  if (nothing_can_be_freed(*cache_)) {
    throw SimulationError(fmt::format("t = {:.6f} s: writing '{}': no memory can be freed for {} bytes", sim_->now(), (*files_)[file].name, bytes));
  }
}

Task<void> IoController::make_room(std::int64_t required, FileId spared, FileId subject, const char* verb) {
  // Planned again at each step: the writeback's transfers let others run, and eviction frees.
  for (;;) {
    co_await write_back(plan_room(*cache_, required).flush, spared, FlushCause::Reclaim);
    if (evict_to_fit(*cache_, required, spared)) co_return;
    if (nothing_can_be_freed(*cache_)) {
      if (subject == kNoFile) {
        throw SimulationError(fmt::format("t = {:.6f} s: {} needs {} bytes of memory, only {} can be freed", sim_->now(), verb, required,
                                          cache_->free()));
      }
      throw SimulationError(fmt::format("t = {:.6f} s: {} '{}' needs {} bytes of memory, only {} can be freed", sim_->now(), verb,
                                        (*files_)[subject].name, required, cache_->free()));
    }
    co_await wait_for_progress();
  }
}

Task<void> IoController::hold_memory(std::int64_t bytes, GroupId group, NodeId node) {
  if (bytes <= 0) co_return;
  co_await take_buffer(bytes, group, kNoFile, "the task's memory", node);
}

Task<void> IoController::take_buffer(std::int64_t bytes, GroupId group, FileId subject, const char* verb, NodeId node) {
  // Room in the group, then in the host; while the host's waited, others of the group may
  // have taken its room again.
  do {
    co_await make_group_room(group, bytes, subject, verb);
    co_await make_room(bytes, kNoFile, subject, verb);
  } while (cache_->group_headroom(group) < bytes);
  cache_->touch_from(node);
  cache_->allocate_anonymous(bytes, group);
}

Task<void> IoController::make_group_room(GroupId group, std::int64_t bytes, FileId subject, const char* verb) {
  // Above memory.high the group reclaims its own clean data, and writes back its dirty data
  // once, but is never refused (mm/memcontrol.c, reclaim_high; the penalty sleep is not
  // modelled).
  if (const std::int64_t over_high = cache_->group_over_high(group, bytes); over_high > 0) {
    const std::int64_t evicted = cache_->evict(over_high, kNoFile, group);
    if (evicted < over_high && co_await write_back(over_high - evicted, kNoFile, FlushCause::Reclaim, group) > 0) {
      cache_->evict(cache_->group_over_high(group, bytes), kNoFile, group);
    }
  }
  for (;;) {
    std::int64_t over = bytes - cache_->group_headroom(group);
    if (over <= 0) co_return;
    const std::int64_t evicted = cache_->evict(over, kNoFile, group);
    over -= evicted;
    if (over <= 0) co_return;
    // Dirty data of the group is written back, then evicted on the next round.
    const std::int64_t flushed = co_await write_back(over, kNoFile, FlushCause::Reclaim, group);
    if (evicted > 0 || flushed > 0) continue;
    if (!nothing_can_be_freed(*cache_)) {
      co_await wait_for_progress();
      continue;
    }
    throw SimulationError(fmt::format(
        "t = {:.6f} s: {} {}: memory group {} is at its limit (memory.max {} bytes, {} in use) and cannot free {} bytes (out of memory in the group)",
        sim_->now(), verb, subject == kNoFile ? std::string() : "'" + (*files_)[subject].name + "'", group, cache_->group_max(group),
        cache_->group_usage(group), over));
  }
}

Task<std::int64_t> IoController::room_for_chunk(FileId file, std::int64_t file_size, std::int64_t bytes, std::int64_t buffer, std::int64_t offset,
                                                GroupId group, const char* verb) {
  const ReadRequest request{.file = file, .file_size = file_size, .bytes = bytes, .anonymous = buffer, .offset = offset};
  const bool in_group = group != kRootGroup;
  if (in_group) cache_->charge_file(file, group);
  // The group is charged with the buffer, and with the new cache data if the file is its own.
  const bool owned = in_group && cache_->group_of(file) == group;
  for (;;) {
    std::int64_t from_disk = -1;
    if (in_group) {
      co_await make_group_room(group, buffer + (owned ? plan_read(*cache_, request).from_disk : 0), file, verb);
      from_disk = evict_for_chunk(*cache_, request);  // as a root group's reader tries before calling
    }
    // While make_room waited, others may have evicted some of this file's data: more of the
    // chunk then comes from the device and needs room too.
    while (from_disk < 0) {
      ReadPlan needs;
      from_disk = evict_for_chunk(*cache_, request, &needs);
      if (from_disk < 0) co_await make_room(needs.required, needs.spared, file, verb);
    }
    // While the host's room was made, others of the group may have taken its room again.
    if (!in_group || cache_->group_headroom(group) >= buffer + (owned ? from_disk : 0)) co_return from_disk;
  }
}

Task<IoTally> IoController::write_chunk(FileId file, std::int64_t chunk, std::int64_t at, NodeId node) {
  const FileInfo& info = (*files_)[file];
  if (info.is_remote()) {
    // No client write cache (the paper's NFS setting): every write goes to the server.
    co_await info.remote.server->serve_write(info.remote.server_file, chunk, *info.remote.route);
    co_return IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
  }
  if (cache_->settings().write_mode == WriteMode::Writethrough) co_return co_await write_chunk_writethrough(file, chunk, at, node);
  co_return co_await write_chunk_writeback(file, chunk, at, node);
}

Task<std::int64_t> IoController::write_to_cache(FileId file, std::int64_t bytes, std::int64_t reclaimed, std::int64_t at, NodeId node) {
  // The pages are taken now and hold the data once the copy is done: the dirty block's entry
  // time is the end of the copy. The file's group is charged for them.
  if (const GroupId group = cache_->group_of(file); group != kRootGroup) {
    const std::int64_t evicted = cache_->evicted_bytes();
    co_await make_group_room(group, bytes, file, "writing");
    reclaimed += cache_->evicted_bytes() - evicted;
    bytes = std::min(bytes, cache_->free());  // others may have taken memory meanwhile
    if (bytes == 0) co_return 0;
  }
  const std::int64_t cold = cold_taken();
  const RemoteTally before = cache_->remote();
  cache_->touch_from(node);
  cache_->reserve(bytes);
  co_await memory(node).write(bytes, std::min(reclaimed, bytes), cold_taken() - cold, remote_since(&RemoteTally::reserved, before, bytes));
  cache_->touch_from(node);
  commit_write(file, at, bytes);
  flusher_->notify_dirty(cache_->group_of(file));
  co_return bytes;
}

// The whole file is written here, chunk after chunk, rather than a coroutine per chunk: with
// many writers each chunk would otherwise create a frame and resume two, all out of cache.
// What is decided between two suspensions is decided by the writer's DirtyThrottle::Writer, so
// that the frame holds little more than it.
void IoController::commit_write(FileId file, std::int64_t at, std::int64_t bytes) {
  if (at == ReadRequest::kWholeFile) cache_->commit_dirty(file, bytes, sim_->now());
  else cache_->commit_dirty_at(file, at, bytes, sim_->now());
}

Task<IoResult> IoController::write_file_throttled(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool whole_file, std::int64_t at,
                                                  NodeId node) {
  const double start = sim_->now();
  if (whole_file) cache_->set_being_written(file, true);
  const double device_bw = (*files_)[file].disk->write_bandwidth();
  const GroupId group = cache_->group_of(file);
  for (std::int64_t offset = 0; offset < bytes; offset += chunk_size) {
    std::int64_t remaining = std::min(chunk_size, bytes - offset);
    DirtyThrottle::Writer writer(throttle_, device_bw, group);
    while (remaining > 0) {
      // What is evicted from here to the copy frees the pages the copy fills.
      std::int64_t evicted = cache_->evicted_bytes();
      const std::int64_t cold = cold_taken();
      const RemoteTally before = cache_->remote();
      cache_->touch_from(node);  // the step's pages are reserved on the writer's node first
      const DirtyThrottle::Step step = writer.next(remaining);
      if (step.kind == DirtyThrottle::Step::Pause) {
        co_await sim_->sleep(step.pause);
        cache_->tracer().throttle(sim_->now() - step.pause);
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
        evicted = cache_->evicted_bytes() - evicted;
        co_await memory(node).write(step.to_cache, std::min(evicted, step.to_cache), cold_taken() - cold,
                                    remote_since(&RemoteTally::reserved, before, step.to_cache));
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
  if (at != ReadRequest::kWholeFile && chunk - cache_->cached_in(file, at, chunk) <= cache_->free()) cache_->read_range(file, at, chunk, sim_->now());
  else if (at == ReadRequest::kWholeFile) cache_->add_clean(file, std::min(chunk, cache_->free()), sim_->now());
  co_return IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
}

namespace {
// `part` of `whole` as a fraction (0 for nothing).
double share(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}
}  // namespace

// read_file and write_file check their request when called, not when their task is awaited.
void IoController::check_request(std::int64_t chunk_size) const {
  if (chunk_size <= 0) throw ConfigError(fmt::format("chunk size must be > 0, got {}", chunk_size));
}

Task<IoResult> IoController::read_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  check_request(chunk_size);
  if ((*files_)[file].is_remote()) return read_remote_file(file, chunk_size, direct, group, node);
  return read_whole_file(file, chunk_size, direct, group, node);
}

RemoteShare IoController::remote_since(std::int64_t RemoteTally::*what, const RemoteTally& before, std::int64_t bytes) const noexcept {
  const RemoteTally& now = cache_->remote();
  return RemoteShare{.source = 0.0, .destination = share(now.*what - before.*what, bytes)};
}

Task<IoResult> IoController::read_whole_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  const double start = sim_->now();
  const FileInfo& info = (*files_)[file];
  // What the loop needs of the file, kept here: with many readers the file's record is out of
  // cache at every chunk, this frame is not.
  const std::int64_t size = info.size;
  const Disk* const disk = info.disk;
  IoTally total;
  ReadCursor cursor;  // where the next chunk's re-access starts: each page once
  // A device whose requests wait: what it reads comes in the kernel's readahead windows.
  std::optional<storage::Readahead> readahead;
  if (!direct && disk->read_ahead() > 0 && disk->request_latency() > 0.0) readahead.emplace(disk->read_ahead(), disk->max_request(), chunk_size);
  for (std::int64_t offset = 0; offset < size; offset += chunk_size) {
    const std::int64_t chunk = std::min(chunk_size, size - offset);
    ++chunks_;
    if (direct) {
      // O_DIRECT: only the application's buffer takes memory; the data comes from the disk.
      const std::int64_t cold = cold_taken();
      const RemoteTally before = cache_->remote();
      co_await take_buffer(chunk, group, file, "reading", node);
      const double rate = memory(node).fresh_copy_rate(share(cold_taken() - cold, chunk), remote_since(&RemoteTally::anonymous, before, chunk));
      co_await disk->read(chunk, rate, chunk);  // requests of the chunk
      total += IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
      continue;
    }
    // One chunk (paper Algorithm 2): room for the application's copy and the new cache copy
    // of what is not cached, then the device and cache reads. Here rather than in a
    // coroutine of its own: a chunk read is the simulator's most frequent operation. The
    // application's buffer is fresh memory: the reader faults in and zeroes each page it
    // copies into; from the disk that overlaps the device's transfer (readahead), from the
    // cache it adds to the copy.
    // A file another task reads by range is held by range: this chunk is its part of it. (The
    // request is made at each use: one kept across the wait would enlarge every reader's frame.)
    const std::int64_t at = cache_->ranged(file) ? offset : ReadRequest::kWholeFile;
    std::int64_t disk_read =
        group == kRootGroup ? evict_for_chunk(*cache_, {.file = file, .file_size = size, .bytes = chunk, .anonymous = chunk, .offset = at}) : -1;
    if (disk_read < 0) disk_read = co_await room_for_chunk(file, size, chunk, chunk, at, group, "reading");
    const std::int64_t cache_read = chunk - disk_read;
    const std::int64_t cold = cold_taken();
    const RemoteTally before = cache_->remote();
    cache_->touch_from(node);
    cursor = start_chunk(*cache_, {.file = file, .file_size = size, .bytes = chunk, .anonymous = chunk, .offset = at}, disk_read, cursor, group,
                         sim_->now());
    // Where the new cache pages, the cached data read and the buffer are, from the reader's node.
    const double buffer_remote = share(cache_->remote().anonymous - before.anonymous, chunk);
    const RemoteShare from_disk{.source = share(cache_->remote().cache - before.cache, disk_read), .destination = buffer_remote};
    const RemoteShare from_cache{.source = share(cache_->remote().reread - before.reread, cache_read), .destination = buffer_remote};
    // Taken back by the host: new cache pages (the device's transfer fills them) and the
    // buffer (the reader's first touch), their faults one after the other (measured: a cold
    // read goes at about 1 / (2 / cold_fault) where both are cold), per byte of the chunk.
    const double cold_share = share(cold_taken() - cold, chunk);
    if (disk_read > 0) {
      double bound = memory(node).fresh_copy_rate(cold_share, from_disk);
      if (readahead) {
        const double rate = static_cast<double>(disk_read) / readahead->seconds(disk_read, disk->request_latency(), disk->read_bandwidth());
        bound = std::min(bound, rate);
      }
      if (cold_share > 0.0) co_await memory(node).device_read(*disk, disk_read, bound, cold_share);
      else co_await disk->read(disk_read, bound);
    }
    if (cache_read > 0) co_await memory(node).read_into_fresh(cache_read, cold_share, from_cache);
    total += IoTally{.bytes = chunk, .cache_bytes = cache_read, .disk_bytes = disk_read};
  }
  co_return file_result(start, sim_->now(), total);
}

Task<IoResult> IoController::write_file(FileId file, std::int64_t bytes, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  check_request(chunk_size);
  cache_->charge_file(file, group);
  const FileInfo& info = (*files_)[file];
  if (!direct && !info.is_remote() && cache_->settings().write_mode == WriteMode::Writeback && throttles_writers()) {
    chunks_ += static_cast<std::uint64_t>((bytes + chunk_size - 1) / chunk_size);
    // A file held by range is written in place, from its start.
    return write_file_throttled(file, bytes, chunk_size, true, cache_->ranged(file) ? 0 : ReadRequest::kWholeFile, node);
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
  const bool in_place = cache_->ranged(file);  // a file held by range is written in place
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

IoController::FlushScratch IoController::take_scratch() {
  if (spare_scratch_.empty()) return {};
  FlushScratch scratch = std::move(spare_scratch_.back());
  spare_scratch_.pop_back();
  return scratch;
}

void IoController::release_scratch(FlushScratch&& scratch) {
  scratch.parts.clear();
  scratch.writes.clear();
  spare_scratch_.push_back(std::move(scratch));
}

Task<void> IoController::fsync(FileId file) {
  const FileInfo& info = (*files_)[file];
  if (info.is_remote()) co_return;  // no client write cache: nothing is dirty here
  std::vector<PageCache::Flushed> taken;
  const std::int64_t bytes = cache_->flush_file(file, taken);
  flushed_ += bytes;
  cache_->tracer().flush(FlushCause::Fsync, bytes);
  if (bytes > 0) co_await info.disk->write(bytes);
  for (const auto& part : taken) cache_->end_writeback(part);
  while (cache_->writeback(file) > 0) co_await wait_for_progress();  // the flusher's, or a writer's
}

Task<void> IoController::drop(FileId file) {
  while (cache_->writeback(file) > 0) co_await wait_for_progress();
  cache_->drop_file(file);
}

}  // namespace pagecache::cache
