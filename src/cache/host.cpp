#include <pagecache/host.hpp>

#include "cache/file_table.hpp"
#include "cache/flusher.hpp"
#include "cache/io_controller.hpp"
#include "cache/page_cache.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>

namespace pagecache {

namespace {
// The host's vCPUs fault memory the host took back in parallel: by default each core at one
// thread's rate.
HostSpec with_defaults(HostSpec spec) {
  MemoryBandwidth& bw = spec.memory_bandwidth;
  if (bw.cold_fault > 0.0 && bw.aggregate_cold_fault <= 0.0) bw.aggregate_cold_fault = bw.cold_fault * std::max(spec.cores, 1);
  return spec;
}
}  // namespace

struct Host::Impl {
  Impl(Simulator& s, FairShare& fs, HostSpec sp)
      : sim(s),
        share(fs),
        spec(with_defaults(std::move(sp))),
        cpu(fs, spec.name + ":cpu", spec.cores),
        memory(fs, spec.name + ":memory", spec.memory_bandwidth),
        cache(spec.memory, spec.cache),
        flusher(s, cache, files),
        io(s, cache, memory, files, flusher) {
    if (cache.policy().copies_hold_cores()) memory.copy_on(&cpu);
  }

  Simulator& sim;
  FairShare& share;
  HostSpec spec;
  Cpu cpu;
  Memory memory;
  std::deque<Disk> disks;  // stable addresses: files point at their disk
  cache::FileTable files;
  cache::PageCache cache;
  cache::Flusher flusher;
  cache::IoController io;
  std::deque<Route> one_link_routes;  // of add_remote_file over a link: stable addresses

  cache::GroupId group(GroupRef g) const {
    if (g.index != 0 && g.index >= cache.group_count()) throw ConfigError(fmt::format("host '{}': unknown memory group #{}", spec.name, g.index));
    return g.index;
  }
  cache::FileId id(FileRef file) const {
    if (file.index >= files.size()) throw ConfigError(fmt::format("host '{}': unknown file #{}", spec.name, file.index));
    return file.index;
  }
};

Host::Host(Simulator& sim, FairShare& share, HostSpec spec) : impl_(std::make_unique<Impl>(sim, share, std::move(spec))) {
  impl_->cache.allocate_anonymous(impl_->spec.memory_in_use);
  impl_->io.machine_at_rest();
  if (impl_->spec.memory_bandwidth.cold_fault > 0.0) impl_->io.report_free_pages(impl_->spec.page_reporting_delay, impl_->spec.memory_freed_at_start);
  if (!(impl_->spec.request_time >= 0.0)) throw ConfigError(fmt::format("host '{}': request_time must be >= 0 s", impl_->spec.name));
  impl_->io.set_request_time(impl_->spec.request_time);
  impl_->flusher.start();
}

Host::~Host() = default;

const std::string& Host::name() const noexcept { return impl_->spec.name; }
const CacheSettings& Host::cache_settings() const noexcept { return impl_->cache.settings(); }

DiskRef Host::add_disk(std::string name, double read_bw, double write_bw, std::int64_t capacity) {
  return add_disk(std::move(name), DiskBandwidth{.read = read_bw, .write = write_bw}, capacity);
}

DiskRef Host::add_disk(std::string name, DiskBandwidth bandwidth, std::int64_t capacity) {
  impl_->disks.emplace_back(impl_->share, std::move(name), bandwidth, capacity);
  return DiskRef{static_cast<std::uint32_t>(impl_->disks.size() - 1)};
}

const Disk& Host::disk(DiskRef disk) const {
  if (disk.index >= impl_->disks.size()) throw ConfigError(fmt::format("host '{}': unknown disk #{}", name(), disk.index));
  return impl_->disks[disk.index];
}

FileRef Host::add_file(std::string name, std::int64_t size, DiskRef disk_ref, bool cached_at_start) {
  const Disk& d = disk(disk_ref);
  if (d.capacity() > 0 && size > d.capacity()) {
    throw ConfigError(fmt::format("file '{}' ({} bytes) does not fit on disk '{}' ({} bytes)", name, size, d.name(), d.capacity()));
  }
  const cache::FileId id = impl_->files.add(std::move(name), size, d);
  impl_->cache.add_file(id);
  if (cached_at_start) impl_->io.cache_at_start(id, size);
  return FileRef{id};
}

FileRef Host::add_remote_file(Host& server, FileRef server_file, const Link& link) {
  return add_remote_file(server, server_file, impl_->one_link_routes.emplace_back(std::vector<const Link*>{&link}));
}

FileRef Host::add_remote_file(Host& server, FileRef server_file, const Route& route) {
  const cache::FileId id = server.impl_->id(server_file);
  const cache::FileInfo& info = server.impl_->files[id];
  const cache::FileId client_id = impl_->files.add_remote(info.name, info.size, cache::RemoteFile{&server.impl_->io, id, &route});
  impl_->cache.add_file(client_id);
  return FileRef{client_id};
}

const std::string& Host::file_name(FileRef file) const { return impl_->files[impl_->id(file)].name; }
std::int64_t Host::file_size(FileRef file) const { return impl_->files[impl_->id(file)].size; }
std::size_t Host::file_count() const noexcept { return impl_->files.size(); }

// IoController's tasks are handed out as they are: a coroutine here would be one frame more
// per file read or written.
Task<IoResult> Host::read_file(FileRef file, std::int64_t chunk_size, bool direct, GroupRef group) {
  return impl_->io.read_file(impl_->id(file), chunk_size, direct, impl_->group(group));
}

Task<IoResult> Host::read_ranges(FileRef file, std::function<bool(ByteRange&)> next, std::int64_t buffer, GroupRef group, ReadAdvice advice,
                                 bool direct) {
  return impl_->io.read_ranges(impl_->id(file), std::move(next), buffer, impl_->group(group), advice, direct);
}

void Host::will_need(FileRef file, ByteRange range) { impl_->io.will_need(impl_->id(file), range); }

std::int64_t Host::dont_need(FileRef file, ByteRange range) { return impl_->io.dont_need(impl_->id(file), range); }

Task<IoResult> Host::write_ranges(FileRef file, std::function<bool(ByteRange&)> next, GroupRef group, bool direct) {
  return impl_->io.write_ranges(impl_->id(file), std::move(next), impl_->group(group), direct);
}

Task<IoResult> Host::write_file(FileRef file, std::int64_t chunk_size, bool direct, GroupRef group) {
  const cache::FileId id = impl_->id(file);
  return impl_->io.write_file(id, impl_->files[id].size, chunk_size, direct, impl_->group(group));
}

Task<void> Host::fsync(FileRef file) { co_await impl_->io.fsync(impl_->id(file)); }

Task<void> Host::delete_file(FileRef file) { co_await impl_->io.drop(impl_->id(file)); }

Task<void> Host::compute(double core_seconds) { co_await impl_->cpu.compute(core_seconds); }

Task<void> Host::hold_memory(std::int64_t bytes, GroupRef group) { co_await impl_->io.hold_memory(bytes, impl_->group(group)); }

void Host::release_memory(std::int64_t bytes, GroupRef group) { impl_->cache.release_anonymous(bytes, impl_->group(group)); }

GroupRef Host::add_memory_group(std::int64_t max, std::int64_t high) { return GroupRef{impl_->cache.add_group(max, high)}; }

std::int64_t Host::group_usage(GroupRef group) const { return impl_->cache.group_usage(impl_->group(group)); }

MemoryState Host::memory() const noexcept { return impl_->cache.memory(); }
std::int64_t Host::cached(FileRef file) const noexcept { return impl_->cache.cached(file.index); }
std::int64_t Host::dirty(FileRef file) const noexcept { return impl_->cache.dirty(file.index); }
std::int64_t Host::forced_flush_bytes() const noexcept { return impl_->io.flushed_bytes(); }
std::int64_t Host::periodic_flush_bytes() const noexcept { return impl_->flusher.flushed_bytes(); }
std::int64_t Host::evicted_bytes() const noexcept { return impl_->cache.evicted_bytes(); }
std::uint64_t Host::chunk_operations() const noexcept { return impl_->io.chunk_operations(); }
std::int64_t Host::peak_dirty_bytes() const noexcept { return impl_->cache.peak_dirty(); }

void Host::set_trace(TraceSink* sink, std::uint32_t index) {
  impl_->cache.set_tracer({.sink = sink, .sim = &impl_->sim, .host = index});
}

void Host::set_memory_observer(std::function<void(double, const MemoryState&)> observer) {
  if (!observer) {
    impl_->cache.set_observer({});
    return;
  }
  impl_->cache.set_observer([impl = impl_.get(), observer = std::move(observer)] { observer(impl->sim.now(), impl->cache.memory()); });
}

void Host::set_checking(bool on) { impl_->cache.set_checking(on); }
void Host::check_invariants() const { impl_->cache.check_invariants(); }

}  // namespace pagecache
