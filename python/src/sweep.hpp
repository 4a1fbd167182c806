#pragma once
// pcsim.sweep's core: `pcsim sweep run` and `merge` in memory (src/sweep/): the plan's runs on
// threads with the GIL released, each as `sweep run` makes it, and results.csv's text.

#include <string>

namespace pcsim_python {

/// The sweep file at `path`, or the sweep file text `text` (named `origin` in messages, its
/// relative paths taken from the working folder) when `path` is empty: every run, `jobs` at a
/// time, and the rows `pcsim sweep merge` would write for them (wall times aside). Ctrl-C
/// stops every run and raises KeyboardInterrupt. Throws ConfigError as the plan does.
std::string sweep_csv(const std::string& path, const std::string& text, const std::string& origin, unsigned jobs, bool force);

}  // namespace pcsim_python
