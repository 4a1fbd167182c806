#include "validate.hpp"

#include "validate/validation.hpp"

#include <pybind11/stl.h>

namespace py = pybind11;

namespace pcsim_python {

namespace {

// -1 is the report's "none" for the read and write means (Exp 1 has none).
py::object mean(double value) { return value < 0.0 ? py::object(py::none()) : py::object(py::float_(value)); }

}  // namespace

py::list validate_cases(const std::string& data_dir, const std::string& scenarios_dir, const std::string& profile,
                        const std::vector<std::pair<std::string, std::string>>& overrides,
                        const std::vector<std::pair<std::string, bool>>& switches) {
  pagecache::validate::Report report;
  {
    py::gil_scoped_release released;
    report = pagecache::validate::run({.data_dir = data_dir, .scenario_dir = scenarios_dir, .profile = profile, .overrides = overrides,
                                       .switches = switches});
    pagecache::validate::check_finite(report);
  }
  py::list cases;
  for (const pagecache::validate::CaseResult& c : report.cases) {
    py::dict d;
    d["case"] = c.name;
    d["profile"] = report.profile;
    d["mean_error_pct"] = c.mean_error_pct;
    d["read_mean_error_pct"] = mean(c.read_mean_error_pct);
    d["write_mean_error_pct"] = mean(c.write_mean_error_pct);
    d["wrench_cache_mean_error_pct"] = c.wrench_mean_error_pct;
    d["wrench_cache_read_mean_error_pct"] = mean(c.wrench_read_mean_error_pct);
    d["wrench_cache_write_mean_error_pct"] = mean(c.wrench_write_mean_error_pct);
    py::dict extra;
    for (const auto& [key, value] : c.extra) extra[py::str(key)] = value;
    d["extra"] = extra;
    py::list figures;
    for (const pagecache::validate::Figure& f : c.figures) {
      figures.append(py::dict(py::arg("label") = f.label, py::arg("real") = f.real, py::arg("simulated") = f.simulated,
                              py::arg("wrench") = f.wrench));
    }
    d["figures"] = figures;
    cases.append(d);
  }
  return cases;
}

}  // namespace pcsim_python
