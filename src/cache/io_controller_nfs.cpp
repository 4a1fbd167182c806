// IoController: NFS. A client reads what its cache lacks from the server (server disk or cache,
// then the route) into its own cache; it writes through to the server, which caches as its own
// settings say.

#include "cache/io_controller.hpp"

#include "cache/chunk_read.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::cache {

Task<IoResult> IoController::read_remote_file(FileId file, std::int64_t chunk_size, bool direct, GroupId group, NodeId node) {
  const double start = sim_->now();
  const std::int64_t size = (*files_)[file].size;
  IoTally total;
  // Where the next chunk's re-access starts, each page once: in this host's cache and in the
  // server's.
  ReadCursor cursor;
  ReadCursor server_cursor;
  for (std::int64_t offset = 0; offset < size; offset += chunk_size) {
    const std::int64_t chunk = std::min(chunk_size, size - offset);
    ++chunks_;
    if (!direct) {
      total += co_await read_chunk_remote(file, chunk, cursor, server_cursor, group, node);
      continue;
    }
    // O_DIRECT: the server serves it as any read, from its cache or its disk, then cached
    // there (the server does not see the client's O_DIRECT); here only the buffer takes memory.
    co_await take_buffer(chunk, group, file, "reading", node);
    co_await serve_remote(file, chunk, &server_cursor, node);
    total += IoTally{.bytes = chunk, .cache_bytes = 0, .disk_bytes = chunk};
  }
  co_return IoResult{.start = start, .end = sim_->now(), .bytes = total.bytes, .cache_bytes = total.cache_bytes, .disk_bytes = total.disk_bytes};
}

Task<IoTally> IoController::read_chunk_remote(FileId file, std::int64_t chunk, ReadCursor& cursor, ReadCursor& server_cursor,
                                              GroupId group, NodeId node) {
  // A client read (NFS): what this host's cache lacks comes from the server, over the link,
  // and is kept in this host's cache (clean); the rest is a hit in this host's cache.
  const FileInfo& info = (*files_)[file];
  const ReadRequest request{.file = file, .file_size = info.size, .bytes = chunk, .anonymous = chunk};
  std::int64_t remote_read = group == kRootGroup ? evict_for_chunk(*cache_, request) : -1;
  if (remote_read < 0) remote_read = co_await room_for_chunk(file, info.size, chunk, chunk, ReadRequest::kWholeFile, group, "reading");
  const std::int64_t cache_read = chunk - remote_read;
  const std::int64_t reread = cache_->nodes().remote().reread;
  cache_->touch_from(node);
  cursor = start_chunk(*cache_, request, remote_read, cursor, group, sim_->now());
  // The part re-read is priced from where it is cached; the server's part by the network.
  const RemoteShare from_cache{.source = share(cache_->nodes().remote().reread - reread, cache_read)};
  if (remote_read > 0) co_await serve_remote(file, remote_read, &server_cursor, node);
  if (cache_read > 0) co_await memory(node).read_into_fresh(cache_read, 0.0, from_cache);
  // From this host's point of view, data from the server is not from its own cache.
  co_return IoTally{.bytes = chunk, .cache_bytes = cache_read, .disk_bytes = remote_read};
}

Task<void> IoController::serve_remote(FileId file, std::int64_t bytes, ReadCursor* server_cursor, NodeId node) {
  // The data lands in this host's memory (its cache, or with O_DIRECT the application's
  // buffer), fresh memory either way. Not a coroutine: the server's frame is all the read
  // holds while it waits, its spec copied there (10^6 clients reading at once).
  const FileInfo& info = (*files_)[file];
  FlowSpec client_copy = memory(node).write_spec(bytes);
  client_copy.bound = std::min(client_copy.bound, memory(node).fresh_copy_rate());
  return info.remote.server->serve_read(info.remote.server_file, bytes, *info.remote.route, client_copy, server_cursor);
}

// Each part of a served read is one flow through the source device, the link and the
// client's memory: the most loaded of them sets the pace; a write through, one flow through
// the link and the disk. Not coroutines: the flow's spec lives in the route's frame, not in
// serve_read's or serve_write's as well.
Task<void> IoController::send_from_disk(const Route& route, const FileInfo& info, const FlowSpec& client_copy, std::int64_t bytes) const {
  FlowSpec spec = client_copy;
  spec.work = static_cast<double>(bytes);
  return route.send_through(info.disk->reading(spec));
}

Task<void> IoController::send_from_cache(const Route& route, const FlowSpec& client_copy, std::int64_t bytes) const {
  const FlowSpec server_copy = memory(0).read_spec(bytes);
  FlowSpec spec = client_copy;
  spec.work = static_cast<double>(bytes);
  spec.bound = std::min(spec.bound, server_copy.bound);
  return route.send_through(spec.through(server_copy.usages[0]));
}

Task<void> IoController::send_to_disk(const Route& route, const FileInfo& info, std::int64_t bytes) const {
  FlowSpec spec{.work = static_cast<double>(bytes)};
  return route.send_through(info.disk->writing(spec));
}

Task<void> IoController::serve_read(FileId file, std::int64_t bytes, const Route& route, FlowSpec client_copy, ReadCursor* cursor) {
  const FileInfo& info = (*files_)[file];
  std::int64_t disk_read = evict_for_chunk(*cache_, ReadRequest{.file = file, .file_size = info.size, .bytes = bytes, .anonymous = 0});
  if (disk_read < 0) disk_read = co_await room_for_chunk(file, info.size, bytes, 0, ReadRequest::kWholeFile, kRootGroup, "serving");
  const std::int64_t cache_read = bytes - disk_read;
  // The client's memory takes the copy: no anonymous memory here.
  cache_->touch_from(0);  // the server's threads: on node 0
  const ReadCursor next = start_chunk(*cache_, ReadRequest{.file = file, .file_size = info.size, .bytes = bytes, .anonymous = 0}, disk_read,
                                      cursor != nullptr ? *cursor : ReadCursor{}, kRootGroup, sim_->now());
  if (cursor != nullptr) *cursor = next;
  if (disk_read > 0) co_await send_from_disk(route, info, client_copy, disk_read);
  if (cache_read > 0) co_await send_from_cache(route, client_copy, cache_read);
}

Task<void> IoController::serve_write(FileId file, std::int64_t bytes, const Route& route) {
  const FileInfo& info = (*files_)[file];
  if (cache_->settings().write_mode == WriteMode::Writethrough) {
    co_await send_to_disk(route, info, bytes);
    cache_->evict(bytes - cache_->free(), file);
    cache_->touch_from(0);  // the server's threads: on node 0
    cache_->add_clean(file, std::min(bytes, cache_->free()), sim_->now());
    co_return;
  }
  co_await route.send(bytes);
  co_await write_chunk_writeback(file, bytes);
}

}  // namespace pagecache::cache
