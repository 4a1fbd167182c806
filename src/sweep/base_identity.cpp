#include "sweep/base_identity.hpp"

#include "formats/common/text_file.hpp"
#include "scenario/toml_reader.hpp"
#include "sweep/hash.hpp"

#include <pagecache/error.hpp>
#include <pagecache/scenario_file.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <filesystem>
#include <optional>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;

std::string hash_of(std::string_view bytes) { return hex16(fnv1a(bytes)); }

// A file named in `base` (a scenario file, or empty: its names are absolute), as the loader
// finds it: relative to the folder of the file naming it.
std::string beside(const std::string& base, const std::string& path) {
  if (base.empty() || fs::path(path).is_absolute()) return path;
  return (fs::path(base).parent_path() / path).lexically_normal().string();
}

std::optional<std::string> string_at(const toml::node* node) {
  if (node == nullptr || !node->is_string()) return std::nullopt;
  return *node->value<std::string>();
}

}  // namespace

std::string BaseIdentity::fingerprint() const {
  std::uint64_t h = kFnvStart;
  for (const BaseFile& f : files) h = fnv1a(f.role + " " + f.hash + "\n", h);
  return hex16(fnv1a("settings " + settings + "\n", h));
}

BaseIdentity identify_base(const std::string& scenario, const std::string& workflow_text, const std::string& profile) {
  BaseIdentity id;
  std::string text;
  std::string named_in;  // the file the base's own names are relative to
  if (!scenario.empty()) {
    text = formats::read_text_file(scenario, "scenario file");
    id.files.push_back({"scenario", scenario, hash_of(text)});
    named_in = scenario;
  } else if (!workflow_text.empty()) {
    text = workflow_text;
  } else {
    text = default_scenario_text();
    id.files.push_back({"scenario", "<embedded default>", hash_of(text)});
  }
  toml::table root;
  try {
    root = toml::parse(text, scenario.empty() ? "<sweep base>" : scenario);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}: {}", scenario::location(e.source(), scenario.empty() ? "<sweep base>" : scenario), e.description()));
  }
  // The platform of the profile in use, as the loader picks it (its default profile: linux).
  const std::string in_use = !profile.empty() ? profile : string_at(root.get("profile")).value_or("linux");
  std::optional<std::string> platform = string_at(root.get("platform"));
  if (const toml::table* per_profile = root["platform"].as_table()) platform = string_at(per_profile->get(in_use));
  std::optional<std::string> workflow = string_at(root.get("workflow"));
  const toml::table* workflow_table = root["workflow"].as_table();
  if (workflow_table != nullptr) workflow = string_at(workflow_table->get("file"));
  if (platform) {
    const std::string path = beside(named_in, *platform);
    id.files.push_back({"platform", path, hash_of(formats::read_text_file(path, "platform file"))});
  }
  if (workflow) {
    const std::string path = beside(named_in, *workflow);
    id.files.push_back({"workflow", path, hash_of(formats::read_text_file(path, "workflow file"))});
  }
  std::vector<std::string> settings;
  if (!profile.empty()) settings.push_back(fmt::format("profile = {}", profile));
  if (!workflow_text.empty() && workflow_table != nullptr) {
    // A sweep's own workflow base: what it says besides the files' names.
    if (const auto host = string_at(workflow_table->get("files_host"))) settings.push_back(fmt::format("files_host = {}", *host));
    if (const toml::array* hosts = (*workflow_table)["hosts"].as_array()) {
      std::vector<std::string> names;
      for (const toml::node& h : *hosts) names.push_back(string_at(&h).value_or(""));
      settings.push_back(fmt::format("hosts = {}", fmt::join(names, ", ")));
    }
  }
  id.settings = fmt::format("{}", fmt::join(settings, "; "));
  return id;
}

std::string base_changes(const BaseIdentity& before, const BaseIdentity& now) {
  if (before.fingerprint() == now.fingerprint()) return {};
  const auto find = [](const BaseIdentity& base, const std::string& role) -> const BaseFile* {
    for (const BaseFile& f : base.files)
      if (f.role == role) return &f;
    return nullptr;
  };
  std::vector<std::string> changes;
  for (const char* role : {"scenario", "platform", "workflow"}) {
    const BaseFile* then = find(before, role);
    const BaseFile* here = find(now, role);
    if (then != nullptr && here != nullptr && then->hash != here->hash) {
      changes.push_back(then->path == here->path
                            ? fmt::format("{} (the {} file) has changed since the folder's runs", here->path, role)
                            : fmt::format("the {} file is {}, not {} as for the folder's runs, and their contents differ", role, here->path, then->path));
    } else if (here != nullptr && then == nullptr) {
      changes.push_back(fmt::format("{} (the {} file) had no part in the folder's runs", here->path, role));
    } else if (then != nullptr && here == nullptr) {
      changes.push_back(fmt::format("{} (the {} file of the folder's runs) has no part in this sweep", then->path, role));
    }
  }
  if (before.settings != now.settings) {
    changes.push_back(fmt::format("the settings are '{}', not '{}' as for the folder's runs", now.settings.empty() ? "none" : now.settings,
                                  before.settings.empty() ? "none" : before.settings));
  }
  if (changes.empty()) changes.push_back(fmt::format("its fingerprint is {}, the folder's {}", now.fingerprint(), before.fingerprint()));
  return fmt::format("{}", fmt::join(changes, "; "));
}

}  // namespace pagecache::sweep
