#include <pagecache/devices.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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
      capacity_(capacity) {
  require_positive(read_bw_, name, "read bandwidth");
  require_positive(write_bw_, name, "write bandwidth");
  require_positive(aggregate_read_bw_, name, "aggregate read bandwidth");
  require_positive(aggregate_write_bw_, name, "aggregate write bandwidth");
  if (aggregate_read_bw_ < read_bw_ || aggregate_write_bw_ < write_bw_) {
    throw ConfigError(fmt::format("{}: an aggregate bandwidth is below one stream's (read {} < {} or write {} < {} B/s)", name,
                                  aggregate_read_bw_, read_bw_, aggregate_write_bw_, write_bw_));
  }
  if (capacity < 0) throw ConfigError(fmt::format("{}: negative capacity {} bytes", name, capacity));
  resource_ = share.add_resource(std::move(name));
}

// A stream as fast as the whole disk needs no bound of its own: its share of the disk is one.
FlowSpec& Disk::reading(FlowSpec& spec) const {
  if (read_bw_ < aggregate_read_bw_) spec.bound = std::min(spec.bound, read_bw_);
  return spec.through(read_usage());
}

FlowSpec& Disk::writing(FlowSpec& spec) const {
  if (write_bw_ < aggregate_write_bw_) spec.bound = std::min(spec.bound, write_bw_);
  return spec.through(write_usage());
}

FlowAwaiter Disk::read(std::int64_t bytes, double bound) const {
  require_bytes(bytes, "disk read");
  FlowSpec spec{.work = static_cast<double>(bytes), .bound = bound};
  return share_->transfer(reading(spec));
}

FlowAwaiter Disk::write(std::int64_t bytes) const {
  require_bytes(bytes, "disk write");
  FlowSpec spec{.work = static_cast<double>(bytes)};
  return share_->transfer(writing(spec));
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
  resource_ = share.add_resource(std::move(name));
}

FlowSpec Memory::read_spec(std::int64_t bytes) const {
  require_bytes(bytes, "memory read");
  return FlowSpec{.work = static_cast<double>(bytes), .bound = bandwidth_.read}.through(
      {resource_, 1.0 / bandwidth_.aggregate_read});
}

FlowSpec Memory::write_spec(std::int64_t bytes, std::int64_t reclaimed) const {
  require_bytes(bytes, "memory write");
  double bound = bandwidth_.write;
  if (reclaimed > 0 && bandwidth_.reclaimed_write > 0.0 && bytes > 0) {
    // The fresh and the reclaimed pages one after the other: the time of both.
    const double from_reclaim = static_cast<double>(std::min(reclaimed, bytes));
    const double seconds = (static_cast<double>(bytes) - from_reclaim) / bandwidth_.write + from_reclaim / bandwidth_.reclaimed_write;
    bound = static_cast<double>(bytes) / seconds;
  }
  return FlowSpec{.work = static_cast<double>(bytes), .bound = bound}.through({resource_, 1.0 / bandwidth_.aggregate_write});
}

FlowSpec Memory::read_into_fresh_spec(std::int64_t bytes) const {
  FlowSpec spec = read_spec(bytes);
  if (bandwidth_.first_touch <= 0.0) return spec;
  spec.bound = fresh_copy_rate();
  spec.usages[0].cost += 1.0 / bandwidth_.aggregate_write;
  return spec;
}

double Memory::fresh_copy_rate() const noexcept {
  if (bandwidth_.first_touch <= 0.0) return kUnbounded;
  return 1.0 / (1.0 / bandwidth_.read + 1.0 / bandwidth_.first_touch);
}

FlowSpec Memory::on_core(FlowSpec spec) const {
  if (cpu_ == nullptr) return spec;
  // At its bound the copy keeps one core busy: 1 / (cores x bound) of the CPU per byte. Its
  // weight is its bound, in bytes per second per core, so that max-min gives it the same
  // share of the cores as a computation (weight 1, in core-seconds per second).
  return spec.through({cpu_->resource(), 1.0 / (cpu_->cores() * spec.bound)}).with_weight(spec.bound);
}

FlowAwaiter Memory::read(std::int64_t bytes) const { return share_->transfer(on_core(read_spec(bytes))); }
FlowAwaiter Memory::read_into_fresh(std::int64_t bytes) const { return share_->transfer(on_core(read_into_fresh_spec(bytes))); }
FlowAwaiter Memory::write(std::int64_t bytes, std::int64_t reclaimed) const {
  return share_->transfer(on_core(write_spec(bytes, reclaimed)));
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
