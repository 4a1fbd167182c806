#pragma once
// An access of parts of one file (AccessSpec with `file`) as the RequestPattern that makes its
// requests, and the check that such a pattern fits its file (for scenarios built in code: the
// loader checks the same key by key).

#include "workload/request_pattern.hpp"

#include <pagecache/scenario.hpp>

#include <cstdint>
#include <string>

namespace pagecache::workload {

/// The requests of `access` (an access of one file): its region, request size, stride, count
/// (0: the pattern's default), draws and ranges.
RequestPattern request_pattern(const AccessSpec& access);

/// Empty if `pattern` is valid over a file of `file_size` bytes; else what is not.
std::string pattern_problem(const RequestPattern& pattern, std::int64_t file_size);

/// The bytes of one epoch of `pattern` (each request's length, summed; a double, as the
/// estimate's figures: a hostile count must not overflow).
double bytes_per_epoch(const RequestPattern& pattern);

}  // namespace pagecache::workload
