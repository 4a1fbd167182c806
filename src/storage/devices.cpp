#include <pagecache/devices.hpp>

#include "storage/readahead.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace pagecache {

namespace {

void require_positive(double value, const std::string& device, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw ConfigError(fmt::format("{}: {} must be a positive finite number, got {}", device, what, value));
  }
}

void require_bytes(std::int64_t bytes, const char* operation) {
  if (bytes < 0) throw SimulationError(fmt::format("{}: negative size {} bytes", operation, bytes));
}

}  // namespace

Disk::Disk(FairShare& share, std::string name, double read_bw, double write_bw, std::int64_t capacity)
    : Disk(share, std::move(name), DiskBandwidth{.read = read_bw, .write = write_bw}, capacity) {}

Disk::Disk(FairShare& share, std::string name, DiskBandwidth bw, std::int64_t capacity)
    : share_(&share),
      read_bw_(bw.read),
      write_bw_(bw.write),
      aggregate_read_bw_(bw.aggregate_read > 0.0 ? bw.aggregate_read : bw.read),
      aggregate_write_bw_(bw.aggregate_write > 0.0 ? bw.aggregate_write : bw.write),
      capacity_(capacity),
      request_latency_(bw.request_latency),
      read_ahead_(bw.read_ahead),
      max_request_(bw.max_request),
      write_cache_(bw.write_cache),
      sustained_write_bw_(bw.sustained_write),
      cache_time_(share.simulator().now()) {
  require_positive(read_bw_, name, "read bandwidth");
  require_positive(write_bw_, name, "write bandwidth");
  require_positive(aggregate_read_bw_, name, "aggregate read bandwidth");
  require_positive(aggregate_write_bw_, name, "aggregate write bandwidth");
  if (aggregate_read_bw_ < read_bw_ || aggregate_write_bw_ < write_bw_) {
    throw ConfigError(fmt::format("{}: an aggregate bandwidth is below one stream's (read {} < {} or write {} < {} B/s)", name,
                                  aggregate_read_bw_, read_bw_, aggregate_write_bw_, write_bw_));
  }
  if (capacity < 0) throw ConfigError(fmt::format("{}: negative capacity {} bytes", name, capacity));
  if (!(request_latency_ >= 0.0) || !std::isfinite(request_latency_)) {
    throw ConfigError(fmt::format("{}: request latency must be >= 0 (0: none), got {} s", name, request_latency_));
  }
  for (const auto& [what, bytes] : {std::pair{"read_ahead", read_ahead_}, std::pair{"max_request", max_request_}}) {
    if (bytes != 0 && bytes < storage::kReadaheadPage) {
      throw ConfigError(fmt::format("{}: {} must be 0 or at least a page ({} bytes), got {}", name, what, storage::kReadaheadPage, bytes));
    }
  }
  if (write_cache_ < 0) throw ConfigError(fmt::format("{}: negative write cache {} bytes", name, write_cache_));
  if (write_cache_ > 0 || sustained_write_bw_ != 0.0) {
    if (write_cache_ == 0) throw ConfigError(fmt::format("{}: a sustained write bandwidth is the medium's behind a write cache: give one", name));
    require_positive(sustained_write_bw_, name, "sustained write bandwidth (behind the write cache)");
    if (sustained_write_bw_ > write_bw_) {
      throw ConfigError(fmt::format("{}: the sustained write bandwidth ({} B/s) is above the write bandwidth ({} B/s)", name,
                                    sustained_write_bw_, write_bw_));
    }
  }
  resource_ = share.add_resource(std::move(name));
}

// A stream as fast as the whole disk needs no bound of its own: its share of the disk is one.
FlowSpec& Disk::reading(FlowSpec& spec, std::int64_t request) const {
  double bound = read_bw_ < aggregate_read_bw_ ? read_bw_ : kUnbounded;
  if (request > 0 && request_latency_ > 0.0) bound = read_request_rate(request);
  spec.bound = std::min(spec.bound, bound);
  return spec.through(read_usage());
}

FlowSpec& Disk::writing(FlowSpec& spec, std::int64_t request) const {
  const bool paced = request > 0 && request_latency_ > 0.0;
  double bound = paced ? write_request_rate(request) : write_bw_ < aggregate_write_bw_ ? write_bw_ : kUnbounded;
  Usage usage = write_usage();
  if (write_cache_ > 0 && spec.work > 0.0) {
    const double burst = fill_write_cache(spec.work);
    if (burst < spec.work) {
      // The burst then the rest at the medium's rate, one after the other: the time of both.
      const double slow = spec.work - burst;
      double seconds = burst / write_bw_ + slow / sustained_write_bw_;
      if (paced) seconds += spec.work / static_cast<double>(request) * request_latency_;
      bound = spec.work / seconds;
      usage.cost = (burst / aggregate_write_bw_ + slow / sustained_write_bw_) / spec.work;
    }
  }
  spec.bound = std::min(spec.bound, bound);
  return spec.through(usage);
}

double Disk::read_request_rate(std::int64_t request) const noexcept {
  if (request <= 0 || request_latency_ <= 0.0) return read_bw_;
  const double r = static_cast<double>(request);
  return r / (request_latency_ + r / read_bw_);
}

double Disk::write_request_rate(std::int64_t request) const noexcept {
  if (request <= 0 || request_latency_ <= 0.0) return write_bw_;
  const double r = static_cast<double>(request);
  return r / (request_latency_ + r / write_bw_);
}

double Disk::write_cache_fill() const {
  if (write_cache_ == 0) return 0.0;
  return std::max(0.0, cache_fill_ - sustained_write_bw_ * (share_->simulator().now() - cache_time_));
}

double Disk::fill_write_cache(double bytes) const {
  const double fill = write_cache_fill();
  cache_fill_ = fill + bytes;
  cache_time_ = share_->simulator().now();
  const double room = static_cast<double>(write_cache_) - fill;
  if (room <= 0.0) return 0.0;
  if (sustained_write_bw_ >= write_bw_) return bytes;
  // The medium drains the cache while the write fills it: it fills at write - sustained.
  return std::min(bytes, room * write_bw_ / (write_bw_ - sustained_write_bw_));
}

FlowAwaiter Disk::read(std::int64_t bytes, double bound, std::int64_t request) const {
  require_bytes(bytes, "disk read");
  require_bytes(request, "disk read request");
  FlowSpec spec{.work = static_cast<double>(bytes), .bound = bound};
  return share_->transfer(reading(spec, request));
}

FlowAwaiter Disk::write(std::int64_t bytes, std::int64_t request) const {
  require_bytes(bytes, "disk write");
  require_bytes(request, "disk write request");
  FlowSpec spec{.work = static_cast<double>(bytes)};
  return share_->transfer(writing(spec, request));
}

Memory::Memory(FairShare& share, std::string name, MemoryBandwidth bandwidth)
    : share_(&share), bandwidth_(bandwidth) {
  require_positive(bandwidth.read, name, "read bandwidth");
  require_positive(bandwidth.write, name, "write bandwidth");
  require_positive(bandwidth.aggregate_read, name, "aggregate read bandwidth");
  require_positive(bandwidth.aggregate_write, name, "aggregate write bandwidth");
  if (!(bandwidth.first_touch >= 0.0) || !std::isfinite(bandwidth.first_touch)) {
    throw ConfigError(fmt::format("{}: first-touch bandwidth must be >= 0 (0: free), got {}", name, bandwidth.first_touch));
  }
  if (!(bandwidth.reclaimed_write >= 0.0) || !std::isfinite(bandwidth.reclaimed_write)) {
    throw ConfigError(fmt::format("{}: write bandwidth into reclaimed pages must be >= 0 (0: as into free pages), got {}", name,
                                  bandwidth.reclaimed_write));
  }
  if (!(bandwidth.cold_fault >= 0.0) || !std::isfinite(bandwidth.cold_fault)) {
    throw ConfigError(fmt::format("{}: the rate of faults into memory the host took back must be >= 0 (0: none taken back), got {}", name,
                                  bandwidth.cold_fault));
  }
  if (bandwidth.cold_fault > 0.0) {
    if (bandwidth_.aggregate_cold_fault <= 0.0) bandwidth_.aggregate_cold_fault = bandwidth.cold_fault;
    require_positive(bandwidth_.aggregate_cold_fault, name, "aggregate rate of faults into memory the host took back");
    faults_ = share.add_resource(name + ":faults");
  }
  resource_ = share.add_resource(std::move(name));
}

void Memory::set_numa(NumaRatios ratios, const std::string& name) {
  for (const double ratio : {ratios.copy, ratios.first_touch, ratios.aggregate}) {
    if (!(ratio > 0.0) || !std::isfinite(ratio)) throw ConfigError(fmt::format("{}: NUMA ratios must be > 0, got {}", name, ratio));
  }
  numa_ = true;
  ratios_ = ratios;
}

namespace {
// Adds `cost` per unit on `resource` to the flow, to its usage if it has one there.
FlowSpec& add_cost(FlowSpec& spec, ResourceId resource, double cost) {
  for (std::size_t i = 0; i < spec.usage_count; ++i) {
    if (spec.usages[i].resource == resource) {
      spec.usages[i].cost += cost;
      return spec;
    }
  }
  return spec.through({resource, cost});
}
}  // namespace

FlowSpec& Memory::load(FlowSpec& spec, double cost, double share) const {
  if (!(share > 0.0) || !numa_) return add_cost(spec, resource_, cost);
  return add_cost(spec, resource_, (1.0 - share) * cost + share * cost / ratios_.aggregate);
}

FlowSpec& Memory::faulting(FlowSpec& spec, double cold_share) const {
  if (!(cold_share > 0.0) || bandwidth_.cold_fault <= 0.0) return spec;
  return spec.through({faults_, cold_share / bandwidth_.aggregate_cold_fault});
}

FlowAwaiter Memory::device_read(const Disk& disk, std::int64_t bytes, double bound, double cold_share) const {
  FlowSpec spec{.work = static_cast<double>(bytes), .bound = bound};
  return share_->transfer(disk.reading(faulting(spec, cold_share)));
}

FlowSpec Memory::read_spec(std::int64_t bytes, RemoteShare remote) const {
  require_bytes(bytes, "memory read");
  if (!numa_) return FlowSpec{.work = static_cast<double>(bytes), .bound = bandwidth_.read}.through({resource_, 1.0 / bandwidth_.aggregate_read});
  // A byte copied is remote when its source or its destination is: the larger share.
  const double share = std::max(remote.source, remote.destination);
  FlowSpec spec{.work = static_cast<double>(bytes), .bound = remote_rate(bandwidth_.read, share, ratios_.copy)};
  return load(spec, 1.0 / bandwidth_.aggregate_read, share);
}

FlowSpec Memory::write_spec(std::int64_t bytes, std::int64_t reclaimed, std::int64_t cold, RemoteShare remote) const {
  require_bytes(bytes, "memory write");
  double bound = bandwidth_.write;
  if (reclaimed > 0 && bandwidth_.reclaimed_write > 0.0 && bytes > 0) {
    // The fresh and the reclaimed pages one after the other: the time of both.
    const double from_reclaim = static_cast<double>(std::min(reclaimed, bytes));
    const double seconds = (static_cast<double>(bytes) - from_reclaim) / bandwidth_.write + from_reclaim / bandwidth_.reclaimed_write;
    bound = static_cast<double>(bytes) / seconds;
  }
  const double cold_share = cold > 0 && bytes > 0 ? static_cast<double>(std::min(cold, bytes)) / static_cast<double>(bytes) : 0.0;
  if (!numa_) {
    FlowSpec spec = FlowSpec{.work = static_cast<double>(bytes), .bound = with_cold(bound, cold_share)}.through({resource_, 1.0 / bandwidth_.aggregate_write});
    return faulting(spec, cold_share);
  }
  const double share = std::max(remote.source, remote.destination);
  bound = remote_rate(bound, share, ratios_.copy);
  FlowSpec spec = FlowSpec{.work = static_cast<double>(bytes), .bound = with_cold(bound, cold_share)};
  load(spec, 1.0 / bandwidth_.aggregate_write, share);
  return faulting(spec, cold_share);
}

FlowSpec Memory::read_into_fresh_spec(std::int64_t bytes, double cold_share, RemoteShare remote) const {
  FlowSpec spec = read_spec(bytes, remote);
  if (bandwidth_.first_touch > 0.0) {
    spec.bound = fresh_copy_rate(0.0, remote);
    load(spec, 1.0 / bandwidth_.aggregate_write, std::max(remote.source, remote.destination));  // the zeroing, beside the copy
  }
  spec.bound = with_cold(spec.bound, cold_share);  // the copy's own rate when first touch is free
  return faulting(spec, cold_share);
}

double Memory::fresh_copy_rate(double cold_share, RemoteShare remote) const noexcept {
  if (bandwidth_.first_touch <= 0.0) return with_cold(kUnbounded, cold_share);
  const double copy = remote_rate(bandwidth_.read, std::max(remote.source, remote.destination), ratios_.copy);
  const double touch = remote_rate(bandwidth_.first_touch, remote.destination, ratios_.first_touch);
  return with_cold(1.0 / (1.0 / copy + 1.0 / touch), cold_share);
}

double Memory::with_cold(double rate, double cold_share) const noexcept {
  if (!(cold_share > 0.0) || bandwidth_.cold_fault <= 0.0) return rate;
  return 1.0 / (1.0 / rate + cold_share / bandwidth_.cold_fault);  // 1 / kUnbounded is 0
}

FlowSpec Memory::on_core(FlowSpec spec) const {
  if (cpu_ == nullptr) return spec;
  // At its bound the copy keeps one core busy: 1 / (cores x bound) of the CPU per byte. Its
  // weight is its bound, in bytes per second per core, so that max-min gives it the same
  // share of the cores as a computation (weight 1, in core-seconds per second).
  return spec.through({cpu_->resource(), 1.0 / (cpu_->cores() * spec.bound)}).with_weight(spec.bound);
}

FlowAwaiter Memory::read(std::int64_t bytes, RemoteShare remote) const { return share_->transfer(on_core(read_spec(bytes, remote))); }
FlowAwaiter Memory::read_into_fresh(std::int64_t bytes, double cold_share, RemoteShare remote) const {
  return share_->transfer(on_core(read_into_fresh_spec(bytes, cold_share, remote)));
}
FlowAwaiter Memory::write(std::int64_t bytes, std::int64_t reclaimed, std::int64_t cold, RemoteShare remote) const {
  return share_->transfer(on_core(write_spec(bytes, reclaimed, cold, remote)));
}

Link::Link(FairShare& share, std::string name, double bandwidth, double latency, LinkSharing sharing)
    : share_(&share), bandwidth_(bandwidth), latency_(latency), sharing_(sharing) {
  require_positive(bandwidth, name, "bandwidth");
  if (!(latency >= 0.0) || !std::isfinite(latency)) {
    throw ConfigError(fmt::format("{}: latency must be >= 0, got {}", name, latency));
  }
  resource_ = share.add_resource(std::move(name));
}

Task<void> Link::send(std::int64_t bytes) const {
  require_bytes(bytes, "link send");
  co_await send_through(FlowSpec{.work = static_cast<double>(bytes)});
}

Task<void> Link::send_through(FlowSpec spec) const {
  carry(spec);
  if (latency_ > 0.0) co_await share_->simulator().sleep(latency_);
  co_await share_->transfer(spec);
}

FlowSpec& Link::carry(FlowSpec& spec) const {
  if (sharing_ == LinkSharing::Fatpipe) return spec.with_bound(std::min(spec.bound, bandwidth_));
  return spec.through(usage());
}

Route::Route(std::vector<const Link*> links) : links_(std::move(links)) {
  if (links_.empty()) throw ConfigError("a route needs at least one link");
  for (const Link* link : links_) latency_ += link->latency();
}

Task<void> Route::send(std::int64_t bytes) const {
  require_bytes(bytes, "route send");
  co_await send_through(FlowSpec{.work = static_cast<double>(bytes)});
}

Task<void> Route::send_through(FlowSpec spec) const {
  for (const Link* link : links_) link->carry(spec);
  if (latency_ > 0.0) co_await links_.front()->share().simulator().sleep(latency_);
  co_await links_.front()->share().transfer(spec);
}

Cpu::Cpu(FairShare& share, std::string name, int cores) : share_(&share), cores_(cores) {
  if (cores <= 0) throw ConfigError(fmt::format("{}: core count must be >= 1, got {}", name, cores));
  resource_ = share.add_resource(std::move(name));
}

FlowAwaiter Cpu::compute(double core_seconds) const {
  if (!(core_seconds >= 0.0)) throw SimulationError(fmt::format("compute: negative CPU time {} s", core_seconds));
  // A task runs on one core at most (bound 1 core-second per second); the cores together are
  // the capacity, so each core-second costs 1 / cores of it.
  return share_->transfer(FlowSpec{.work = core_seconds, .bound = 1.0}.through({resource_, 1.0 / cores_}));
}

}  // namespace pagecache
