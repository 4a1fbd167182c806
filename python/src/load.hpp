#pragma once
// A scenario as Python hands it over (pcsim/_scenario.py decides which kind): a file, TOML
// text, a workflow instance's file, or the embedded default; with the options `pcsim run`
// takes (--set, --profile, --platform, --files-host, --hosts).

#include <pagecache/scenario.hpp>

#include <string>
#include <utility>
#include <vector>

namespace pcsim_python {

struct LoadRequest {
  std::string kind;    ///< "file", "text", "workflow" or "default"
  std::string source;  ///< the path, or the TOML text
  std::string name;    ///< what outputs and messages call it (empty: the path, or "<text>")
  std::vector<std::pair<std::string, std::string>> overrides;  ///< (dotted key, TOML value)
  std::string profile;
  std::string platform;
  std::string files_host;
  std::vector<std::string> hosts;
};

/// Throws pagecache::ConfigError as the command line's loading does, naming the request's name.
pagecache::Scenario load(const LoadRequest& request);

}  // namespace pcsim_python
