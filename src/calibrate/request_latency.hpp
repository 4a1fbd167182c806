#pragma once
// The device's time per request apart from the bytes: O_DIRECT reads at several request sizes,
// fitted as time per request = latency + size / bandwidth. Small requests show the latency,
// large ones the bandwidth; the platform keeps the latency and the large-request rate.

#include "calibrate/figure.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pagecache::calibrate {

/// O_DIRECT sequential reads of one file, one stream, in requests of `size` bytes.
struct RequestRate {
  std::int64_t size = 0;
  Figure rate;
};

/// The fit; not `fitted` (fewer than two sizes measured): `why` says so.
struct RequestFit {
  bool fitted = false;
  double latency = 0.0;    ///< seconds per request, >= 0
  double bandwidth = 0.0;  ///< bytes per second: the fit's slope
  bool clamped = false;    ///< the unconstrained fit gave a negative latency: 0, slope refitted
  std::string why;
};

/// Least squares on the time per request (size / rate), each weighted by 1 / time^2: the rates'
/// noise is a fraction of each, and unweighted the largest requests' noise swamps the latency.
RequestFit fit_request_latency(const std::vector<RequestRate>& rates);

/// The platform's `request_latency` line, above it the table of sizes and the fit.
std::string request_latency_toml(const std::vector<RequestRate>& rates, const RequestFit& fit, std::int64_t file_size);

}  // namespace pagecache::calibrate
