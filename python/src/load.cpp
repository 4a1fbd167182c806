#include "load.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <toml++/toml.h>

#include <filesystem>
#include <sstream>

namespace pcsim_python {

namespace {

// `text` as a TOML string value.
std::string toml_string(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

std::string absolute(const std::string& path) { return std::filesystem::absolute(path).lexically_normal().string(); }

}  // namespace

pagecache::Scenario load(const LoadRequest& r) {
  if (r.kind == "workflow") {
    pagecache::WorkflowOptions options{.platform = r.platform, .files_host = r.files_host, .hosts = r.hosts};
    pagecache::Scenario s = pagecache::load_workflow(r.source, options, r.overrides, r.profile);
    if (!r.name.empty()) s.source = r.name;  // a dict's instance: not the file it was handed over in
    return s;
  }
  if (!r.files_host.empty() || !r.hosts.empty()) {
    throw pagecache::ConfigError("files_host and hosts place a workflow instance's files and tasks; a scenario gives them in its [workflow] table");
  }
  auto overrides = r.overrides;
  // A scenario on another platform: `platform` is its platform key, as --platform is.
  if (!r.platform.empty()) overrides.insert(overrides.begin(), {"platform", toml_string(absolute(r.platform))});
  if (r.kind == "default") return pagecache::parse_scenario(pagecache::default_scenario_text(), "<embedded default>", overrides, r.profile);
  if (r.kind == "text") return pagecache::parse_scenario(r.source, r.name.empty() ? "<text>" : r.name, overrides, r.profile);
  if (r.kind == "file") return pagecache::load_scenario(r.source, overrides, r.profile);
  throw pagecache::ConfigError("pcsim: unknown kind of scenario '" + r.kind + "'");
}

}  // namespace pcsim_python
