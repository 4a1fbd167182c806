#include <pagecache/host.hpp>

#include "cache/file_table.hpp"
#include "cache/flusher.hpp"
#include "cache/io_controller.hpp"
#include "cache/page_cache.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <deque>
#include <optional>

namespace pagecache {

namespace {
// The host's vCPUs fault memory the host took back in parallel: by default each core at one
// thread's rate.
HostSpec with_defaults(HostSpec spec) {
  MemoryBandwidth& bw = spec.memory_bandwidth;
  if (bw.cold_fault > 0.0 && bw.aggregate_cold_fault <= 0.0) bw.aggregate_cold_fault = bw.cold_fault * std::max(spec.cores, 1);
  return spec;
}

// The host's NUMA nodes as its model has them (one unless numa_nodes).
int modelled_nodes(const HostSpec& spec) {
  if (spec.numa.nodes < 1 || spec.numa.nodes > cache::kMaxNodes) {
    throw ConfigError(fmt::format("host '{}': a host has 1 to {} NUMA nodes, got {}", spec.name, cache::kMaxNodes, spec.numa.nodes));
  }
  return spec.cache.numa_nodes ? spec.numa.nodes : 1;
}

// One NUMA node's memory bandwidth: its share of the host's aggregates, a thread's own rates.
MemoryBandwidth node_bandwidth(const HostSpec& spec, int nodes) {
  MemoryBandwidth bw = spec.memory_bandwidth;
  if (nodes <= 1) return bw;
  bw.aggregate_read /= nodes, bw.aggregate_write /= nodes, bw.aggregate_cold_fault /= nodes;
  return bw;
}

std::string memory_name(const HostSpec& spec, int nodes, int node) {
  return nodes <= 1 ? spec.name + ":memory" : fmt::format("{}:node{} memory", spec.name, node);
}
}  // namespace

struct Host::Impl {
  Impl(Simulator& s, FairShare& fs, HostSpec sp)
      : sim(s),
        share(fs),
        spec(with_defaults(std::move(sp))),
        cpu(fs, spec.name + ":cpu", spec.cores),
        nodes(modelled_nodes(spec)),
        memory(fs, memory_name(spec, nodes, 0), node_bandwidth(spec, nodes)),
        cache(spec.memory, spec.cache, {.nodes = nodes}),
        flusher(s, cache, files),
        io(s, cache, memory, files, flusher) {
    if (nodes > 1) {
      other_node.emplace(fs, memory_name(spec, nodes, 1), node_bandwidth(spec, nodes));
      memory.set_numa(spec.numa.remote, spec.name);
      other_node->set_numa(spec.numa.remote, spec.name);
      io.set_node_memory(1, *other_node);
    }
    // The copy is a memcpy by the application's thread (copy_page_to_iter, copy_page_from_iter).
    if (spec.cache.copies_hold_cores) {
      memory.copy_on(&cpu);
      if (other_node) other_node->copy_on(&cpu);
    }
  }

  Simulator& sim;
  FairShare& share;
  HostSpec spec;
  Cpu cpu;
  int nodes;                         // NUMA nodes modelled
  Memory memory;                     // node 0's on a NUMA host
  std::optional<Memory> other_node;  // node 1's memory
  std::array<int, cache::kMaxNodes> running{};  // threads running on each node
  std::deque<Disk> disks;  // stable addresses: files point at their disk
  cache::FileTable files;
  cache::PageCache cache;
  cache::Flusher flusher;
  cache::IoController io;
  std::deque<Route> one_link_routes;  // of add_remote_file over a link: stable addresses

  cache::GroupId group(GroupRef g) const {
    if (g.index != 0 && g.index >= cache.groups().size()) throw ConfigError(fmt::format("host '{}': unknown memory group #{}", spec.name, g.index));
    return g.index;
  }
  cache::NodeId node(NodeRef n) const {
    if (n.index >= cache.nodes().count()) throw ConfigError(fmt::format("host '{}': unknown NUMA node #{}", spec.name, n.index));
    return n.index;
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
Task<IoResult> Host::read_file(FileRef file, std::int64_t chunk_size, bool direct, Thread thread) {
  return impl_->io.read_file(impl_->id(file), chunk_size, direct, impl_->group(thread.group), impl_->node(thread.node));
}

Task<IoResult> Host::read_ranges(FileRef file, std::function<bool(ByteRange&)> next, std::int64_t buffer, Thread thread, ReadAdvice advice,
                                 bool direct) {
  return impl_->io.read_ranges(impl_->id(file), std::move(next), buffer, impl_->group(thread.group), advice, direct, impl_->node(thread.node));
}

void Host::will_need(FileRef file, ByteRange range) { impl_->io.will_need(impl_->id(file), range); }

std::int64_t Host::dont_need(FileRef file, ByteRange range) { return impl_->io.dont_need(impl_->id(file), range); }

Task<IoResult> Host::write_ranges(FileRef file, std::function<bool(ByteRange&)> next, Thread thread, bool direct) {
  return impl_->io.write_ranges(impl_->id(file), std::move(next), impl_->group(thread.group), direct, impl_->node(thread.node));
}

Task<IoResult> Host::write_file(FileRef file, std::int64_t chunk_size, bool direct, Thread thread) {
  const cache::FileId id = impl_->id(file);
  return impl_->io.write_file(id, impl_->files[id].size, chunk_size, direct, impl_->group(thread.group), impl_->node(thread.node));
}

Task<void> Host::fsync(FileRef file) { co_await impl_->io.fsync(impl_->id(file)); }

Task<void> Host::delete_file(FileRef file) { co_await impl_->io.drop(impl_->id(file)); }

Task<void> Host::compute(double core_seconds) { co_await impl_->cpu.compute(core_seconds); }

Task<void> Host::hold_memory(std::int64_t bytes, Thread thread) {
  co_await impl_->io.hold_memory(bytes, impl_->group(thread.group), impl_->node(thread.node));
}

void Host::release_memory(std::int64_t bytes, Thread thread) {
  impl_->cache.touch_from(impl_->node(thread.node));
  impl_->cache.release_anonymous(bytes, impl_->group(thread.group));
}

Thread Host::start_thread(GroupRef group) {
  const auto nodes = static_cast<std::size_t>(impl_->cache.nodes().count());
  std::size_t node = 0;
  for (std::size_t n = 1; n < nodes; ++n) {
    if (impl_->running[n] < impl_->running[node]) node = n;
  }
  ++impl_->running[node];
  return Thread{group, NodeRef{static_cast<std::uint8_t>(node)}};
}

void Host::end_thread(Thread thread) { --impl_->running[impl_->node(thread.node)]; }

int Host::nodes() const noexcept { return static_cast<int>(impl_->cache.nodes().count()); }

GroupRef Host::add_memory_group(std::int64_t max, std::int64_t high) { return GroupRef{impl_->cache.add_group(max, high)}; }

std::int64_t Host::group_usage(GroupRef group) const { return cache::group_usage(impl_->cache, impl_->group(group)); }

MemoryState Host::memory() const noexcept { return impl_->cache.memory(); }
std::int64_t Host::cached(FileRef file) const noexcept { return impl_->cache.file(file.index).cached(); }
std::int64_t Host::dirty(FileRef file) const noexcept { return impl_->cache.file(file.index).dirty; }
std::int64_t Host::forced_flush_bytes() const noexcept { return impl_->io.flushed_bytes(); }
std::int64_t Host::periodic_flush_bytes() const noexcept { return impl_->flusher.flushed_bytes(); }
std::int64_t Host::evicted_bytes() const noexcept { return impl_->cache.totals().evicted; }
std::uint64_t Host::chunk_operations() const noexcept { return impl_->io.chunk_operations(); }
std::int64_t Host::peak_dirty_bytes() const noexcept { return impl_->cache.totals().peak_dirty; }

void Host::set_trace(TraceSink* sink, std::uint32_t index) {
  impl_->cache.listeners().tracer = {.sink = sink, .sim = &impl_->sim, .host = index};
}

void Host::set_memory_observer(std::function<void(double, const MemoryState&)> observer) {
  if (!observer) {
    impl_->cache.listeners().change = {};
    return;
  }
  impl_->cache.listeners().change = [impl = impl_.get(), observer = std::move(observer)] { observer(impl->sim.now(), impl->cache.memory()); };
}

void Host::set_checking(bool on) { impl_->cache.set_checking(on); }
void Host::check_invariants() const { impl_->cache.check_invariants(); }

}  // namespace pagecache
