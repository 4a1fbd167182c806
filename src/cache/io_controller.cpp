#include "cache/io_controller.hpp"

#include "cache/chunk_read.hpp"

#include "engine/check.hpp"
#include "storage/readahead.hpp"

#include <pagecache/units.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::cache {

Task<std::int64_t> IoController::write_back(std::int64_t amount, FileId excluded, FlushCause cause, GroupId group) {
  if (amount <= 0) co_return 0;
  FlushScratch scratch = take_scratch();
  std::vector<PageCache::Flushed>& taken = scratch.parts;
  const std::int64_t total = cache_->flush(amount, excluded, taken, group);
  flushed_ += total;
  cache_->listeners().tracer.flush(cause, total);
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
  cache_->listeners().progress = [this] {
    if (progress_ && !progress_->triggered()) progress_->trigger();
  };
}

bool IoController::throttles_writers() const noexcept { return cache_->policy().throttles_writers(); }

void IoController::machine_at_rest() { throttle_.at_rest(); }

void IoController::report_free_pages(double delay, std::int64_t warm) {
  reporting_.emplace(cache_->free(), cache_->memory().anonymous, warm, delay, cache_->settings().large_folios);
  cache_->listeners().free_memory = [this](std::int64_t free, std::int64_t anonymous) { reporting_->observe(free, anonymous, sim_->now()); };
}

void IoController::cache_at_start(FileId file, std::int64_t bytes) {
  if (!reporting_) {
    cache_->add_clean(file, bytes, sim_->now());
    return;
  }
  // Cached before the run: its memory was neither freed nor taken by the run.
  cache_->listeners().free_memory = {};
  cache_->add_clean(file, bytes, sim_->now());
  reporting_->rebase(cache_->free(), cache_->memory().anonymous);
  cache_->listeners().free_memory = [this](std::int64_t free, std::int64_t anonymous) { reporting_->observe(free, anonymous, sim_->now()); };
}

Task<void> IoController::wait_for_progress() {
  if (!progress_ || progress_->triggered()) progress_.emplace(*sim_);
  co_await progress_->wait();
}

void IoController::check_writer_can_wait(FileId file, std::int64_t bytes) const {
  if (nothing_can_be_freed(*cache_)) {
    throw SimulationError(fmt::format("t = {} s: writing '{}': no memory can be freed for {} bytes", units::format_instant(sim_->now()), (*files_)[file].name, bytes));
  }
}

Task<void> IoController::make_room(std::int64_t required, FileId spared, FileId subject, const char* verb) {
  // Planned again at each step: the writeback's transfers let others run, and eviction frees.
  for (;;) {
    co_await write_back(plan_room(*cache_, required).flush, spared, FlushCause::Reclaim);
    if (evict_to_fit(*cache_, required, spared)) co_return;
    if (nothing_can_be_freed(*cache_)) {
      if (subject == kNoFile) {
        throw SimulationError(fmt::format("t = {} s: {} needs {} bytes of memory, only {} can be freed", units::format_instant(sim_->now()), verb, required,
                                          cache_->free()));
      }
      throw SimulationError(fmt::format("t = {} s: {} '{}' needs {} bytes of memory, only {} can be freed", units::format_instant(sim_->now()), verb,
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
  } while (cache_->groups().headroom(group) < bytes);
  cache_->touch_from(node);
  cache_->allocate_anonymous(bytes, group);
}

Task<void> IoController::make_group_room(GroupId group, std::int64_t bytes, FileId subject, const char* verb) {
  // Above memory.high the group reclaims its own clean data, and writes back its dirty data
  // once, but is never refused (mm/memcontrol.c, reclaim_high; the penalty sleep is not
  // modelled).
  if (const std::int64_t over_high = cache_->groups().over_high(group, bytes); over_high > 0) {
    const std::int64_t evicted = cache_->evict(over_high, kNoFile, group);
    if (evicted < over_high && co_await write_back(over_high - evicted, kNoFile, FlushCause::Reclaim, group) > 0) {
      cache_->evict(cache_->groups().over_high(group, bytes), kNoFile, group);
    }
  }
  for (;;) {
    std::int64_t over = bytes - cache_->groups().headroom(group);
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
        "t = {} s: {} {}: memory group {} is at its limit (memory.max {} bytes, {} in use) and cannot free {} bytes (out of memory in the group)",
        units::format_instant(sim_->now()), verb, subject == kNoFile ? std::string() : "'" + (*files_)[subject].name + "'", group, cache_->groups().max(group),
        group_usage(*cache_, group), over));
  }
}

Task<std::int64_t> IoController::room_for_chunk(FileId file, std::int64_t file_size, std::int64_t bytes, std::int64_t buffer, std::int64_t offset,
                                                GroupId group, const char* verb) {
  const ReadRequest request{.file = file, .file_size = file_size, .bytes = bytes, .anonymous = buffer, .offset = offset};
  const bool in_group = group != kRootGroup;
  if (in_group) cache_->charge_file(file, group);
  // The group is charged with the buffer, and with the new cache data if the file is its own.
  const bool owned = in_group && cache_->groups().of(file) == group;
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
    if (!in_group || cache_->groups().headroom(group) >= buffer + (owned ? from_disk : 0)) co_return from_disk;
  }
}

// read_file and write_file check their request when called, not when their task is awaited.
void IoController::check_request(std::int64_t chunk_size) const {
  if (chunk_size <= 0) throw ConfigError(fmt::format("chunk size must be > 0, got {}", chunk_size));
}

Task<IoResult> IoController::read_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  check_request(chunk_size);
  if ((*files_)[file].is_remote()) return read_remote_file(file, chunk_size, direct, group, node);
  return read_whole_file(file, chunk_size, direct, group, node);
}

IoController::ChunkCopies IoController::start_read_chunk(const ReadRequest& request, std::int64_t disk_read, ReadCursor& cursor, GroupId group,
                                                         NodeId node, storage::Readahead* readahead, const Disk& disk) {
  const std::int64_t cold = cold_taken();
  const RemoteTally before = cache_->nodes().remote();
  cache_->touch_from(node);
  cursor = start_chunk(*cache_, request, disk_read, cursor, group, sim_->now());
  ChunkCopies copies;
  // Taken back by the host: new cache pages (the device's transfer fills them) and the buffer
  // (the reader's first touch), their faults one after the other (measured: a cold read goes
  // at about 1 / (2 / cold_fault) where both are cold), per byte of the chunk.
  copies.cold_share = share(cold_taken() - cold, request.bytes);
  // Where the new cache pages, the cached data read and the buffer are, from the reader's node.
  RemoteShare from_disk;
  if (numa_) {
    const RemoteTally& now = cache_->nodes().remote();
    const double buffer = share(now.anonymous - before.anonymous, request.bytes);
    from_disk = RemoteShare{.source = share(now.cache - before.cache, disk_read), .destination = buffer};
    copies.remote = RemoteShare{.source = share(now.reread - before.reread, request.bytes - disk_read), .destination = buffer};
  }
  if (disk_read > 0) {
    copies.bound = memory(node).fresh_copy_rate(copies.cold_share, from_disk);
    if (readahead != nullptr) {
      copies.bound = std::min(copies.bound, static_cast<double>(disk_read) / readahead->seconds(disk_read, disk.request_latency(), disk.read_bandwidth()));
    }
  }
  return copies;
}

RemoteShare IoController::remote_since(std::int64_t RemoteTally::*what, std::int64_t before, std::int64_t bytes) const noexcept {
  return RemoteShare{.source = 0.0, .destination = share(cache_->nodes().remote().*what - before, bytes)};
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
      const std::int64_t placed = cache_->nodes().remote().anonymous;
      co_await take_buffer(chunk, group, file, "reading", node);
      const double rate = memory(node).fresh_copy_rate(share(cold_taken() - cold, chunk), remote_since(&RemoteTally::anonymous, placed, chunk));
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
    const std::int64_t at = cache_->ranges().tracked(file) ? offset : ReadRequest::kWholeFile;
    std::int64_t disk_read =
        group == kRootGroup ? evict_for_chunk(*cache_, {.file = file, .file_size = size, .bytes = chunk, .anonymous = chunk, .offset = at}) : -1;
    if (disk_read < 0) disk_read = co_await room_for_chunk(file, size, chunk, chunk, at, group, "reading");
    const std::int64_t cache_read = chunk - disk_read;
    const ChunkCopies copies = start_read_chunk({.file = file, .file_size = size, .bytes = chunk, .anonymous = chunk, .offset = at}, disk_read,
                                                cursor, group, node, readahead ? &*readahead : nullptr, *disk);
    if (disk_read > 0) {
      if (copies.cold_share > 0.0) co_await memory(node).device_read(*disk, disk_read, copies.bound, copies.cold_share);
      else co_await disk->read(disk_read, copies.bound);
    }
    if (cache_read > 0) co_await memory(node).read_into_fresh(cache_read, copies.cold_share, copies.remote);
    total += IoTally{.bytes = chunk, .cache_bytes = cache_read, .disk_bytes = disk_read};
  }
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
  cache_->listeners().tracer.flush(FlushCause::Fsync, bytes);
  if (bytes > 0) co_await info.disk->write(bytes);
  for (const auto& part : taken) cache_->end_writeback(part);
  while (cache_->writeback(file) > 0) co_await wait_for_progress();  // the flusher's, or a writer's
}

Task<void> IoController::drop(FileId file) {
  while (cache_->writeback(file) > 0) co_await wait_for_progress();
  cache_->drop_file(file);
}

}  // namespace pagecache::cache
