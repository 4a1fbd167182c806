#pragma once
// A run's rows as columns: numpy arrays that own their memory, names as categorical codes and
// their categories, for pandas to wrap without a copy or a Python object per row.

#include <pagecache/run.hpp>

#include <pybind11/pybind11.h>

namespace pcsim_python {

/// timeline.csv's columns: app, task, host, phase (each "<name>_codes" and "<name>_categories"),
/// start_s, end_s, bytes, cache_bytes, disk_bytes.
pybind11::dict timeline_columns(const pagecache::RunResult& result);
/// memory.csv's columns: host (codes, categories), time_s and the byte counts, copies in
/// flight counted as cached and inactive as memory.csv counts them.
pybind11::dict memory_columns(const pagecache::RunResult& result);
/// cache.csv's columns: app, task, phase, file (codes, categories) and cached_bytes.
pybind11::dict cache_columns(const pagecache::RunResult& result);

}  // namespace pcsim_python
