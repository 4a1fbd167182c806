#include "calibrate/write_cache.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <sys/statvfs.h>

namespace pagecache::calibrate {

namespace {

double median_rate(std::vector<Rate>::const_iterator first, std::vector<Rate>::const_iterator last) {
  std::vector<double> v;
  for (auto it = first; it != last; ++it) v.push_back(it->per_second());
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double spread_pct(std::vector<Rate>::const_iterator first, std::vector<Rate>::const_iterator last) {
  const double median = median_rate(first, last);
  if (first == last || median <= 0.0) return 0.0;
  const auto [low, high] = std::minmax_element(first, last, [](const Rate& a, const Rate& b) { return a.per_second() < b.per_second(); });
  return (high->per_second() - low->per_second()) / median * 100.0;
}

// Free bytes an ordinary user may still write on the file system of `dir`; -1 if unknown.
std::int64_t free_bytes(const std::filesystem::path& dir) {
  struct statvfs vfs{};
  if (::statvfs(dir.c_str(), &vfs) != 0) return -1;
  return static_cast<std::int64_t>(vfs.f_bavail) * static_cast<std::int64_t>(vfs.f_frsize);
}

std::string exact_size(std::int64_t bytes) {
  if (bytes % GiB == 0) return fmt::format("{} GiB", bytes / GiB);
  return fmt::format("{} MiB", bytes / MiB);
}

std::string rates_text(const std::vector<Rate>& pieces) {
  std::string out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out += fmt::format("{}{:.0f}", i % 16 == 0 ? "\n#   " : " ", pieces[i].per_second() / 1e6);
  }
  return out;
}

}  // namespace

WriteCacheFinding find_write_cache(const std::vector<Rate>& pieces) {
  WriteCacheFinding f;
  const auto begin = pieces.begin();
  for (std::size_t at = 1; at + kFallPieces <= pieces.size(); ++at) {
    const double before = median_rate(begin, begin + static_cast<std::ptrdiff_t>(at));
    const double limit = kFallRatio * before;
    const bool low_run = std::all_of(begin + static_cast<std::ptrdiff_t>(at), begin + static_cast<std::ptrdiff_t>(at + kFallPieces),
                                     [&](const Rate& r) { return r.per_second() < limit; });
    if (!low_run || median_rate(begin + static_cast<std::ptrdiff_t>(at), pieces.end()) >= limit) continue;
    f.fell = true;
    f.fall = at;
    for (std::size_t i = 0; i < at; ++i) f.cache_bytes += pieces[i].bytes;
    f.burst = before;
    f.sustained = median_rate(begin + static_cast<std::ptrdiff_t>(at), pieces.end());
    f.spread_pct = spread_pct(begin + static_cast<std::ptrdiff_t>(at), pieces.end());
    return f;
  }
  f.burst = f.sustained = median_rate(pieces.begin(), pieces.end());
  f.spread_pct = spread_pct(pieces.begin(), pieces.end());
  return f;
}

bool write_rate_settled(const std::vector<Rate>& pieces) {
  const WriteCacheFinding f = find_write_cache(pieces);
  if (!f.fell || pieces.size() - f.fall < kFallPieces) return false;
  const auto last = pieces.end() - static_cast<std::ptrdiff_t>(kFallPieces);
  return spread_pct(last, pieces.end()) <= kSettledWithin * 100.0;
}

WriteCache measure_write_cache(const std::filesystem::path& dir, const Scratch& scratch, const WriteCacheSetting& setting) {
  WriteCache w;
  w.setting = setting;
  w.free_before = free_bytes(dir);
  // Never more than half the free space: the file system is shared, and others write too.
  const std::int64_t keep = w.free_before / 2;
  const std::int64_t most = std::min(setting.most, keep) / setting.piece * setting.piece;
  const std::int64_t least = static_cast<std::int64_t>(2 * kFallPieces) * setting.piece;
  if (most < least) {
    w.why = fmt::format("half the file system's free space ({}) is under {} pieces of {}", size_text(std::max<std::int64_t>(0, keep)),
                        2 * kFallPieces, size_text(setting.piece));
    return w;
  }
  const std::filesystem::path file = scratch.file("write-cache");
  {
    DirectAppender appender(file, setting.request);
    const Deadline deadline(setting.seconds);
    std::int64_t written = 0;
    while (true) {
      if (written + setting.piece > most) {
        w.stopped = most < setting.most ? fmt::format("half the file system's free space ({} written)", size_text(most))
                                         : fmt::format("the bound of {} written", size_text(most));
        break;
      }
      if (const std::int64_t now = free_bytes(dir); now >= 0 && now - setting.piece < keep) {
        w.stopped = fmt::format("half the file system's free space when it began ({} written, the rest taken by others meanwhile)",
                                size_text(written));
        break;
      }
      const Rate r = appender.append(setting.piece, deadline);
      written += r.bytes;
      if (r.bytes >= setting.piece / 2 && r.seconds > 0.0) w.pieces.push_back(r);  // a short last piece is too noisy
      if (appender.full()) {
        w.stopped = "the file system refused more (no room)";
        break;
      }
      if (deadline.passed()) {
        w.stopped = stop_requested() ? "interrupted" : fmt::format("the time bound ({:.0f} s)", setting.seconds);
        break;
      }
      if (write_rate_settled(w.pieces)) {
        w.stopped = "settled after the fall";
        break;
      }
    }
  }
  scratch.remove(file);
  w.measured = !w.pieces.empty();
  if (!w.measured) w.why = "nothing measured (interrupted?)";
  w.finding = find_write_cache(w.pieces);
  return w;
}

std::string write_cache_toml(const WriteCache& w, double write_bw) {
  if (!w.measured) return fmt::format("# write_cache, sustained_write_bw not set: {}\n", w.why);
  std::int64_t bytes = 0;
  double seconds = 0.0;
  for (const Rate& r : w.pieces) {
    bytes += r.bytes;
    seconds += r.seconds;
  }
  const WriteCacheFinding& f = w.finding;
  std::string out = fmt::format("# O_DIRECT sequential writes of random data, one stream, {} requests, in pieces of {}, each timed, until the "
                                "rate settled after a fall or a bound ({:.0f} s, half the free space, {}): {} pieces ({}) in {:.1f} s, "
                                "ended by {}; rates in MB/s, in order:{}\n",
                                size_text(w.setting.request), size_text(w.setting.piece), w.setting.seconds, size_text(w.setting.most),
                                w.pieces.size(), size_text(bytes), seconds, w.stopped, rates_text(w.pieces));
  if (w.setting.quick) {
    return out + fmt::format("# write_cache, sustained_write_bw not set: --quick, too little written to find a device's write cache ({}: median "
                             "{}, spread {:.0f} %)\n",
                             f.fell ? "a fall seen" : "no fall seen", rate_text(f.sustained), f.spread_pct);
  }
  if (!f.fell) {
    return out + fmt::format("# write_cache, sustained_write_bw not set: no write cache found: {} at {} (median), rates within {:.0f} % "
                             "((max - min) / median), never {} pieces in a row under {:.0f} % of the rate before them\n",
                             size_text(bytes), rate_text(f.sustained), f.spread_pct, kFallPieces, kFallRatio * 100.0);
  }
  const std::string fall = fmt::format("the rate fell from {} (median of the {} pieces before) to under {:.0f} % of it from piece {} on, "
                                       "after {}",
                                       rate_text(f.burst), f.fall, kFallRatio * 100.0, f.fall + 1, exact_size(f.cache_bytes));
  if (write_bw <= 0.0) return out + fmt::format("# write_cache, sustained_write_bw not set: {}, but write_bw, their burst rate, was not measured\n", fall);
  if (f.sustained > write_bw) {
    return out + fmt::format("# write_cache, sustained_write_bw not set: {}, to {} (median after), above write_bw ({}, writeback's): writeback "
                             "does not slow below write_bw when the cache is full\n",
                             fall, rate_text(f.sustained), rate_text(write_bw));
  }
  // pcsim's medium drains the cache while it fills (at sustained_write_bw): a cache that took
  // the bytes before the fall at the burst rate holds that much less.
  const double held = static_cast<double>(f.cache_bytes) * (1.0 - f.sustained / f.burst);
  const std::int64_t capacity = std::max<std::int64_t>(MiB, static_cast<std::int64_t>(held / static_cast<double>(MiB) + 0.5) * MiB);
  out += fmt::format("# {}; the medium draining it at the sustained rate meanwhile (as pcsim's does), it holds {} x (1 - {:.0f}/{:.0f})\n"
                     "write_cache = \"{}\"\n",
                     fall, exact_size(f.cache_bytes), f.sustained / 1e6, f.burst / 1e6, exact_size(capacity));
  out += fmt::format("# median of the {} pieces from the fall on (spread {:.0f} %)\nsustained_write_bw = \"{}\"\n", w.pieces.size() - f.fall,
                     f.spread_pct, rate_text(f.sustained));
  return out;
}

}  // namespace pagecache::calibrate
