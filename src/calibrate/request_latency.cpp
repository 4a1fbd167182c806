#include "calibrate/request_latency.hpp"

#include "calibrate/text.hpp"

#include <fmt/format.h>

namespace pagecache::calibrate {

RequestFit fit_request_latency(const std::vector<RequestRate>& rates) {
  // Weighted least squares of t = a + b s with weights w = 1 / t^2 (t: seconds per request).
  double sw = 0.0, ss = 0.0, st = 0.0, sss = 0.0, sst = 0.0;
  int sizes = 0;
  for (const RequestRate& r : rates) {
    if (!r.rate.measured || r.rate.value <= 0.0 || r.size <= 0) continue;
    const double s = static_cast<double>(r.size);
    const double t = s / r.rate.value;
    const double w = 1.0 / (t * t);
    sw += w;
    ss += w * s;
    st += w * t;
    sss += w * s * s;
    sst += w * s * t;
    ++sizes;
  }
  RequestFit fit;
  const double det = sw * sss - ss * ss;
  if (sizes < 2 || det <= 0.0) {
    fit.why = "fewer than two request sizes measured";
    return fit;
  }
  fit.fitted = true;
  double a = (sss * st - ss * sst) / det;
  double b = (sw * sst - ss * st) / det;
  if (a < 0.0 || b <= 0.0) {
    // Latency held at 0: the slope alone, through the origin.
    a = 0.0;
    b = sst / sss;
    fit.clamped = true;
  }
  fit.latency = a;
  fit.bandwidth = b > 0.0 ? 1.0 / b : 0.0;
  return fit;
}

std::string request_latency_toml(const std::vector<RequestRate>& rates, const RequestFit& fit, std::int64_t file_size) {
  if (rates.empty()) return "# request_latency not set: " + (fit.why.empty() ? std::string("not measured") : fit.why) + "\n";
  std::string out = fmt::format("# O_DIRECT sequential reads of one {} file, one stream, by request size (rate, spread of its repetitions):\n",
                                size_text(file_size));
  for (const RequestRate& r : rates) {
    const std::string size = r.size >= MiB ? fmt::format("{} MiB", r.size / MiB) : fmt::format("{} KiB", r.size / 1024);
    if (!r.rate.measured) out += fmt::format("#   {:>8}  not measured\n", size);
    else out += fmt::format("#   {:>8}  {:>6.0f} MB/s  {:>3.0f} %  {:.3f} ms per request\n", size, r.rate.value / 1e6, r.rate.spread_pct,
                            static_cast<double>(r.size) / r.rate.value * 1e3);
  }
  if (!fit.fitted) return out + fmt::format("# request_latency not set: {}\n", fit.why);
  out += fmt::format("# fitted as time per request = request_latency + size / bandwidth (least squares on the time per request, weighted by "
                     "1/time^2): bandwidth {}{}\n",
                     rate_text(fit.bandwidth), fit.clamped ? "; the unconstrained fit's latency was negative: held at 0" : "");
  return out + fmt::format("request_latency = \"{:.3f} ms\"\n", fit.latency * 1e3);
}

}  // namespace pagecache::calibrate
