#pragma once
// pcsim.validate's core: `pcsim validate`'s comparison with the paper's measurements
// (src/validate/validation.hpp), its cases handed over as dicts.

#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

namespace pcsim_python {

/// The cases of `pcsim validate --data DATA --scenarios SCENARIOS [--profile P] [--set ...]
/// [--switch NAME=VALUE ...]`, each a dict: case, the mean errors (None where the case has
/// none), its other figures (extra) and its compared durations (figures: label, real,
/// simulated, wrench). Runs with the GIL released.
pybind11::list validate_cases(const std::string& data_dir, const std::string& scenarios_dir, const std::string& profile,
                              const std::vector<std::pair<std::string, std::string>>& overrides,
                              const std::vector<std::pair<std::string, bool>>& switches);

}  // namespace pcsim_python
