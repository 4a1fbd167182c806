#include "columns.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

namespace py = pybind11;

namespace pcsim_python {

namespace {

// A numpy array over `values`, which it keeps alive: no copy.
template <class T>
py::array_t<T> to_array(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

// Names of one column as codes into categories of their own, in order of first appearance
// (RunResult::names holds the applications' and the tasks' names together).
class Categories {
 public:
  explicit Categories(const std::vector<std::string>& names) : names_(&names), code_(names.size(), -1) {}
  std::int32_t code(std::uint32_t name) {
    if (code_[name] < 0) {
      code_[name] = static_cast<std::int32_t>(categories_.size());
      categories_.push_back((*names_)[name]);
    }
    return code_[name];
  }
  py::list list() const { return py::cast(categories_); }

 private:
  const std::vector<std::string>* names_;
  std::vector<std::int32_t> code_;
  std::vector<std::string> categories_;
};

py::list phase_categories() {
  py::list out;
  for (auto kind : {pagecache::PhaseKind::Read, pagecache::PhaseKind::Compute, pagecache::PhaseKind::Write}) {
    out.append(std::string(pagecache::to_string(kind)));
  }
  return out;
}

}  // namespace

py::dict timeline_columns(const pagecache::RunResult& r) {
  const std::size_t n = r.timeline.size();
  Categories apps(r.names), tasks(r.names);
  std::vector<std::int32_t> app(n), task(n), host(n);
  std::vector<std::int8_t> phase(n);
  std::vector<double> start(n), end(n);
  std::vector<std::int64_t> bytes(n), cache_bytes(n), disk_bytes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const pagecache::PhaseRow& p = r.timeline[i];
    app[i] = apps.code(p.app);
    task[i] = tasks.code(p.task);
    host[i] = static_cast<std::int32_t>(p.host);
    phase[i] = static_cast<std::int8_t>(p.phase);
    start[i] = p.start;
    end[i] = p.end;
    bytes[i] = p.bytes;
    cache_bytes[i] = p.cache_bytes;
    disk_bytes[i] = p.disk_bytes;
  }
  py::dict d;
  d["app_codes"] = to_array(std::move(app));
  d["app_categories"] = apps.list();
  d["task_codes"] = to_array(std::move(task));
  d["task_categories"] = tasks.list();
  d["host_codes"] = to_array(std::move(host));
  d["host_categories"] = py::cast(r.hosts);
  d["phase_codes"] = to_array(std::move(phase));
  d["phase_categories"] = phase_categories();
  d["start_s"] = to_array(std::move(start));
  d["end_s"] = to_array(std::move(end));
  d["bytes"] = to_array(std::move(bytes));
  d["cache_bytes"] = to_array(std::move(cache_bytes));
  d["disk_bytes"] = to_array(std::move(disk_bytes));
  return d;
}

py::dict memory_columns(const pagecache::RunResult& r) {
  const std::size_t n = r.memory.size();
  std::vector<std::int32_t> host(n);
  std::vector<double> time(n);
  std::vector<std::int64_t> total(n), free(n), anonymous(n), cached(n), dirty(n), writeback(n), active(n), inactive(n);
  for (std::size_t i = 0; i < n; ++i) {
    const pagecache::MemoryRow& m = r.memory[i];
    const pagecache::MemoryState& s = m.state;
    host[i] = static_cast<std::int32_t>(m.host);
    time[i] = m.time;
    total[i] = s.total;
    free[i] = s.free;
    anonymous[i] = s.anonymous;
    cached[i] = s.cached + s.reserved;  // as memory.csv: copies in flight hold their pages
    dirty[i] = s.dirty;
    writeback[i] = s.writeback;
    active[i] = s.active;
    inactive[i] = s.inactive + s.reserved;
  }
  py::dict d;
  d["host_codes"] = to_array(std::move(host));
  d["host_categories"] = py::cast(r.hosts);
  d["time_s"] = to_array(std::move(time));
  d["total_bytes"] = to_array(std::move(total));
  d["free_bytes"] = to_array(std::move(free));
  d["anonymous_bytes"] = to_array(std::move(anonymous));
  d["cached_bytes"] = to_array(std::move(cached));
  d["dirty_bytes"] = to_array(std::move(dirty));
  d["writeback_bytes"] = to_array(std::move(writeback));
  d["active_bytes"] = to_array(std::move(active));
  d["inactive_bytes"] = to_array(std::move(inactive));
  return d;
}

py::dict cache_columns(const pagecache::RunResult& r) {
  const std::size_t n = r.cache.size();
  Categories apps(r.names), tasks(r.names);
  std::vector<std::int32_t> app(n), task(n), file(n);
  std::vector<std::int8_t> phase(n);
  std::vector<std::int64_t> cached(n);
  for (std::size_t i = 0; i < n; ++i) {
    const pagecache::CacheRow& c = r.cache[i];
    const pagecache::PhaseRow& p = r.timeline[c.phase];
    app[i] = apps.code(p.app);
    task[i] = tasks.code(p.task);
    phase[i] = static_cast<std::int8_t>(p.phase);
    file[i] = static_cast<std::int32_t>(c.file);
    cached[i] = c.cached;
  }
  py::dict d;
  d["app_codes"] = to_array(std::move(app));
  d["app_categories"] = apps.list();
  d["task_codes"] = to_array(std::move(task));
  d["task_categories"] = tasks.list();
  d["phase_codes"] = to_array(std::move(phase));
  d["phase_categories"] = phase_categories();
  d["file_codes"] = to_array(std::move(file));
  d["file_categories"] = py::cast(r.files);
  d["cached_bytes"] = to_array(std::move(cached));
  return d;
}

}  // namespace pcsim_python
