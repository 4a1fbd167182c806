// pcsim._core: the C++ side of the Python module pcsim (python/pcsim/ is the Python side, which
// users import). It loads scenarios, runs them with the GIL released, and hands over the
// results as columns; errors become pcsim.InputError and pcsim.SimulationError.

#include "columns.hpp"
#include "load.hpp"
#include "sweep.hpp"
#include "validate.hpp"

#include <pagecache/error.hpp>
#include <pagecache/outputs.hpp>
#include <pagecache/run.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/version.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace pcsim_python {

namespace {

// Ctrl-C seen during a run: the run stops, and Python gets its KeyboardInterrupt.
struct Interrupted {};

// A finished run: the scenario's names (for the outputs), the results, and the recorders of
// report.html and trace.json.
class Run {
 public:
  Run(pagecache::Scenario named, pagecache::RunResult result, std::unique_ptr<pagecache::RunOutputs> outputs)
      : named_(std::move(named)), result_(std::move(result)), outputs_(std::move(outputs)) {}

  std::string summary_json() const { return pagecache::summary_json(named_, result_); }
  std::string timing_json() const { return pagecache::timing_json(result_); }
  std::string readable_summary() const { return pagecache::readable_summary(named_, result_); }
  std::string report_html() const { return outputs_->report_html(named_, result_); }
  std::string cache_not_recorded() const { return result_.cache_not_recorded; }
  std::vector<std::string> warnings() const { return named_.warnings; }
  std::vector<std::string> write(const std::string& dir) {
    if (written_) throw pagecache::ConfigError("a Result is written once: its report's and trace's recorders are freed as they are written");
    written_ = true;
    return outputs_->write(dir, named_, result_);
  }
  const pagecache::RunResult& result() const { return result_; }

 private:
  pagecache::Scenario named_;  // its source, title and profile name the outputs
  pagecache::RunResult result_;
  std::unique_ptr<pagecache::RunOutputs> outputs_;
  bool written_ = false;
};

// What the outputs name of the scenario (its file, title and profile), as `pcsim run` keeps it
// while the run frees the rest; and its warnings, for Result.warnings.
pagecache::Scenario names_of(const pagecache::Scenario& s) {
  pagecache::Scenario named;
  named.source = s.source;
  named.title = s.title;
  named.profile = s.profile;
  named.fio = s.fio;  // fio.json's jobs
  named.warnings = s.warnings;
  return named;
}

std::unique_ptr<Run> simulate(pagecache::Scenario scenario, bool trace, bool cache_contents) {
  pagecache::RunOptions options;
  options.cache_contents = cache_contents;
  options.progress = [](double, std::uint64_t) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw Interrupted{};
  };
  auto outputs = std::make_unique<pagecache::RunOutputs>(pagecache::OutputSettings{.report = true, .trace = trace || scenario.trace});
  outputs->attach(options);
  pagecache::Scenario named = names_of(scenario);
  pagecache::RunResult result;
  try {
    py::gil_scoped_release released;
    result = pagecache::run_scenario(std::move(scenario), options);
  } catch (const Interrupted&) {
    throw py::error_already_set();  // PyErr_CheckSignals left the KeyboardInterrupt set
  }
  return std::make_unique<Run>(std::move(named), std::move(result), std::move(outputs));
}

// pcsim._errors' classes, raised with the structured parts of the C++ exception.
void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const pagecache::ConfigError& e) {
    const pagecache::InputPlace& place = e.place();
    py::object type = py::module_::import("pcsim._errors").attr("InputError");
    py::object error = type(e.what(), place.file.empty() ? py::none() : py::cast(place.file),
                            place.line == 0 ? py::none() : py::cast(place.line), place.key.empty() ? py::none() : py::cast(place.key));
    PyErr_SetObject(type.ptr(), error.ptr());
  } catch (const pagecache::SimulationError& e) {
    py::object type = py::module_::import("pcsim._errors").attr("SimulationError");
    PyErr_SetObject(type.ptr(), type(e.what()).ptr());
  } catch (const pagecache::InvariantError& e) {
    py::object type = py::module_::import("pcsim._errors").attr("InvariantError");
    PyErr_SetObject(type.ptr(), type(e.what()).ptr());
  } catch (const pagecache::Error& e) {
    py::object type = py::module_::import("pcsim._errors").attr("Error");
    PyErr_SetObject(type.ptr(), type(e.what()).ptr());
  }
}

}  // namespace

}  // namespace pcsim_python

PYBIND11_MODULE(_core, m) {
  using namespace pcsim_python;
  m.doc() = "pcsim's C++ core; import pcsim instead";
  m.attr("__version__") = pagecache::kVersion;
  py::register_exception_translator(&translate);

  py::class_<LoadRequest>(m, "LoadRequest")
      .def(py::init<>())
      .def_readwrite("kind", &LoadRequest::kind)
      .def_readwrite("source", &LoadRequest::source)
      .def_readwrite("name", &LoadRequest::name)
      .def_readwrite("overrides", &LoadRequest::overrides)
      .def_readwrite("profile", &LoadRequest::profile)
      .def_readwrite("platform", &LoadRequest::platform)
      .def_readwrite("files_host", &LoadRequest::files_host)
      .def_readwrite("hosts", &LoadRequest::hosts);

  py::class_<pagecache::Scenario>(m, "Scenario")
      .def_property_readonly("source", [](const pagecache::Scenario& s) { return s.source; })
      .def_property_readonly("title", [](const pagecache::Scenario& s) { return s.title; })
      .def_property_readonly("profile", [](const pagecache::Scenario& s) { return std::string(pagecache::to_string(s.profile)); })
      .def_property_readonly("warnings", [](const pagecache::Scenario& s) { return s.warnings; })
      .def("to_toml", [](const pagecache::Scenario& s) { return pagecache::to_toml(s); });

  m.def("load", &load, py::arg("request"), "A scenario as the request says (pcsim._scenario builds it).");
  m.def(
      "run", [](const LoadRequest& request, bool trace, bool cache_contents) { return simulate(load(request), trace, cache_contents); },
      py::arg("request"), py::arg("trace"), py::arg("cache_contents"),
      "Loads the scenario and runs it to its end, the GIL released (the scenario is the run's: no copy).");

  m.def("validate_cases", &validate_cases, py::arg("data_dir"), py::arg("scenarios_dir"), py::arg("profile"), py::arg("overrides"),
        py::arg("switches"), "pcsim validate's cases (pcsim.validate makes its tables from them).");

  m.def("sweep_csv", &sweep_csv, py::arg("path"), py::arg("text"), py::arg("origin"), py::arg("jobs"), py::arg("force"),
        "pcsim sweep run + merge in memory: every run of the sweep file (path) or sweep text, jobs at a time on threads with the "
        "GIL released; results.csv's text (pcsim.sweep makes its table from it).");

  py::class_<Run>(m, "Run")
      .def("summary_json", &Run::summary_json)
      .def("timing_json", &Run::timing_json)
      .def("readable_summary", &Run::readable_summary)
      .def("report_html", &Run::report_html)
      .def("cache_not_recorded", &Run::cache_not_recorded)
      .def("warnings", &Run::warnings)
      .def("write", &Run::write, py::arg("folder"))
      .def("timeline_columns", [](const Run& r) { return timeline_columns(r.result()); })
      .def("memory_columns", [](const Run& r) { return memory_columns(r.result()); })
      .def("cache_columns", [](const Run& r) { return cache_columns(r.result()); });
}
