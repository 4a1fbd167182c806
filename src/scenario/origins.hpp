#pragma once
// Where each element of a resolved scenario was written (its table, the table's key path and
// its file), so that checks made on the whole scenario can still name a file, line and key.

#include "scenario/toml_reader.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pagecache::scenario {

struct Origin {
  const toml::table* table = nullptr;
  std::string path;
  const std::string* file = nullptr;
  /// Elements not read from TOML (a platform's XML, a workflow's JSON): where they were, e.g.
  /// "p.xml:12: host 'a'", named in place of a TOML key's file, line and path.
  std::string place;

  Origin() = default;
  Origin(const toml::table* t, std::string p, const std::string* f) : table(t), path(std::move(p)), file(f) {}
  static Origin elsewhere(std::string place) {
    Origin o;
    o.place = std::move(place);
    return o;
  }

  bool has(const std::string& key) const { return table != nullptr && table->contains(key); }
  /// "file:line:col: key 'path.key': message" (see TomlReader::fail), or "place: key: message".
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    if (table == nullptr) throw ConfigError(place + ": " + key + ": " + message);
    TomlReader(*table, path, *file).fail(key, message);
  }
  [[noreturn]] void fail_table(const std::string& message) const {
    if (table == nullptr) throw ConfigError(place + ": " + message);
    TomlReader(*table, path, *file).fail_table(message);
  }
};

/// The origins of a scenario's elements, in the Scenario's order. The applications and files
/// a [pipelines] table makes are all that table's: the first `pipeline_apps` applications and
/// the files after the [[files]] tables'.
struct Origins {
  Origin root;
  std::vector<Origin> hosts;
  /// Host groups ([[hosts]] with count): name -> (index of the first member, members).
  std::map<std::string, std::pair<std::size_t, std::size_t>> host_groups;
  std::vector<Origin> page_caches;  ///< per host: its [hosts.page_cache], else the host's table
  std::vector<std::vector<Origin>> disks;  ///< per host
  std::vector<Origin> links;
  std::vector<Origin> routes;
  std::vector<Origin> files;  ///< the [[files]] tables
  std::vector<Origin> file_sets;  ///< the [[file_sets]] tables
  std::optional<Origin> pipelines;
  std::size_t pipeline_apps = 0;
  std::vector<Origin> apps;  ///< the [[apps]] tables, after the pipelines' applications
  std::vector<std::vector<Origin>> app_tasks;
  std::vector<Origin> workflows;
  std::vector<std::vector<Origin>> workflow_tasks;

  const Origin& file(std::size_t i) const { return i < files.size() ? files[i] : *pipelines; }
  bool from_pipelines(std::size_t app) const { return app < pipeline_apps; }
  const Origin& app(std::size_t i) const { return from_pipelines(i) ? *pipelines : apps[i - pipeline_apps]; }
  const Origin& app_task(std::size_t app, std::size_t task) const {
    return from_pipelines(app) ? *pipelines : app_tasks[app - pipeline_apps][task];
  }
};

}  // namespace pagecache::scenario
