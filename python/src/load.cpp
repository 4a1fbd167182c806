#include "load.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

namespace pcsim_python {

pagecache::Scenario load(const LoadRequest& r) {
  pagecache::RunInputs in;
  in.workflow = {.platform = r.platform, .files_host = r.files_host, .hosts = r.hosts};
  in.overrides = r.overrides;
  in.profile = r.profile;
  if (r.kind == "text") return pagecache::parse_run_scenario(r.source, r.name.empty() ? "<text>" : r.name, in);
  if (r.kind != "default" && r.kind != "file" && r.kind != "workflow") throw pagecache::ConfigError("pcsim: unknown kind of scenario '" + r.kind + "'");
  pagecache::Scenario s = pagecache::load_run_scenario(r.kind == "default" ? std::string() : r.source, in);
  if (r.kind == "workflow" && !r.name.empty()) s.source = r.name;  // a dict's instance: not the file it was handed over in
  return s;
}

}  // namespace pcsim_python
