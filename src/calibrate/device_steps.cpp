// calibrate's steps that measure the device: O_DIRECT streams, writeback, buffered reads, its write cache.
#include "calibrate/steps.hpp"

#include "calibrate/measure.hpp"
#include "calibrate/text.hpp"
#include "calibrate/write_cache.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pagecache::calibrate {

BufferedReading buffered_reading(const Calibration& c) {
  const std::int64_t request = std::min(MiB, c.request);
  return {request, fmt::format("buffered read (read(), {} requests, kernel readahead) of a file dropped from the cache "
                               "(POSIX_FADV_DONTNEED)",
                               size_text(request))};
}

bool measure_streams(Calibration& c, Session& s, const std::filesystem::path& one, const std::vector<std::filesystem::path>& many) {
  const int repeat = s.budget.repeat;
  const double disk_seconds = s.budget.disk_seconds;
  try {
    s.next("device: write, one stream");
    c.disk_write = repeated(kOnce, [&](int) { return direct_write(one, c.size, c.request, Deadline(disk_seconds)); },
                            fmt::format("O_DIRECT sequential write, one stream, {} requests (the fdatasync after it not timed)", size_text(c.request)));
    s.next("device: read, one stream");
    c.disk_read = repeated(repeat, [&](int) { return direct_read(one, c.request, Deadline(disk_seconds)); },
                           fmt::format("O_DIRECT sequential read, one stream, {} requests", size_text(c.request)));
    s.next("device: read, one stream, by request size");
    for (const std::int64_t size : {MiB / 16, MiB / 4, MiB, 4 * MiB, 16 * MiB}) {
      if (size >= c.request) break;
      c.request_rates.push_back(RequestRate{size, repeated(repeat, [&](int) { return direct_read(one, size, Deadline(disk_seconds)); }, "")});
    }
    c.request_rates.push_back(RequestRate{c.request, c.disk_read});
    c.request_fit = fit_request_latency(c.request_rates);
    s.next(fmt::format("device: write, {} streams", c.streams));
    c.disk_aggregate_write = repeated(
        kOnce,
        [&](int) {
          const Deadline together(disk_seconds);
          return concurrently(many, [&](const std::filesystem::path& f) { return direct_write(f, c.size, c.request, together); });
        },
        fmt::format("O_DIRECT sequential writes, {} streams at once", c.streams));
    s.next(fmt::format("device: read, {} streams", c.streams));
    c.disk_aggregate_read = repeated(
        repeat,
        [&](int) {
          const Deadline together(disk_seconds);
          return concurrently(many, [&](const std::filesystem::path& f) { return direct_read(f, c.request, together); });
        },
        fmt::format("O_DIRECT sequential reads, {} streams at once", c.streams));
  } catch (const DirectIoUnsupported& e) {
    c.notes.push_back(fmt::format("{}: the device is measured through the page cache instead (buffered, synced or dropped)", e.what()));
    c.request_rates.clear();
    c.request_fit = RequestFit{};
    c.request_fit.why = "the file system refuses O_DIRECT";
    s.step = 5;  // the five O_DIRECT steps are skipped
    return false;
  }
  return true;
}

// Under half the background threshold (no writeback before the clock starts) and about what
// the O_DIRECT write did in a second (a slow disk is not given minutes of work).
void measure_writeback(Calibration& c, Session& s, const std::vector<std::filesystem::path>& many) {
  s.next(fmt::format("device: writeback, one file and {} at once", c.streams));
  const std::filesystem::path synced = s.scratch.file("writeback");
  std::int64_t dirty = std::min(c.size, background_limit(s.sys) / 2);
  if (c.disk_write.measured) dirty = std::min(dirty, static_cast<std::int64_t>(c.disk_write.value));  // about a second's
  dirty = std::max(c.request, dirty / c.request * c.request);
  const std::int64_t dirty_each = std::max(c.request, dirty / c.streams / c.request * c.request);
  c.writeback = repeated(
      s.budget.repeat,
      [&](int) {
        const Rate r = writeback({synced}, dirty, c.request);
        s.scratch.remove(synced);
        return r;
      },
      fmt::format("writeback: fsync of {} just written through the page cache (the write not timed), one file", size_text(dirty)));
  c.aggregate_writeback = repeated(
      s.budget.repeat,
      [&](int) {
        const Rate r = writeback(many, dirty_each, c.request);
        for (const auto& f : many) s.scratch.remove(f);
        return r;
      },
      fmt::format("writeback: {} files of {} just written, fsync of each at once", c.streams, size_text(dirty_each)));
}

// Each page of the cache the read fills is memory just freed (as much freed right before,
// after the writeback files' pages), as a task reading after others' work freed memory gets.
void measure_buffered_read(Calibration& c, Session& s, const std::filesystem::path& one, bool direct) {
  s.next("device: buffered read, for comparison");
  if (!direct) buffered_write_synced(one, c.size, c.request, Deadline(s.budget.disk_seconds));
  const BufferedReading reading = buffered_reading(c);
  {
    MemoryHold freed(s.sys.page_size);
    freed.add(c.size);
  }
  c.buffered_read = figure(buffered_read_cold(one, reading.request, Deadline(s.budget.disk_seconds)), reading.how + ", into memory just freed");
  sync_and_drop(one);
  if (!s.budget.cold) s.scratch.remove(one);
  if (!direct) {
    c.disk_read = c.buffered_read;
    c.disk_aggregate_read = c.disk_read;
  }
}

// Last of all, as what it writes may keep a host's or a controller's cache busy for a while after.
void measure_device_write_cache(Calibration& c, Session& s, bool direct) {
  s.next("device: write until a write cache fills");
  if (!direct) {
    c.write_cache.why = "the file system refuses O_DIRECT";
    return;
  }
  WriteCacheSetting w;
  w.request = c.request;
  w.quick = s.options.quick;
  if (s.options.quick) {
    // A check that the measurement works, not a measurement.
    w.piece = std::max(c.request, c.size / 4 / c.request * c.request);
    w.most = 16 * w.piece;
    w.seconds = 2.0;
  } else {
    w.piece = std::max(c.request, 256 * MiB / c.request * c.request);
    w.most = 64 * GiB;
    w.seconds = std::clamp(225.0 - s.elapsed(), 15.0, 60.0);  // about a minute, within the four
  }
  c.write_cache = measure_write_cache(s.options.dir, s.scratch, w);
}

}  // namespace pagecache::calibrate
