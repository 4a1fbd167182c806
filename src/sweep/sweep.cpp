#include "sweep/sweep.hpp"

#include "formats/common/json_text.hpp"
#include "formats/common/text_file.hpp"
#include "scenario/toml_reader.hpp"
#include "sweep/hash.hpp"
#include "sweep/sweep_values.hpp"
#include "text/json_string.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;
using scenario::location;

std::string absolute_beside(const std::string& path, const std::string& file) {
  const fs::path p(path);
  return (p.is_absolute() ? p : fs::absolute(fs::path(file).parent_path() / p)).lexically_normal().string();
}

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}: {}", location(e.source(), path), e.description()));
  }
}

// The sweep file's top-level keys, as read.
struct SweepFile {
  std::optional<std::string> scenario, workflow, platform, files_host;
  std::vector<std::string> hosts;
  std::string profile;
  std::vector<const toml::table*> axes, points;
};

SweepFile read_sweep_file(scenario::TomlReader& r) {
  SweepFile f;
  f.scenario = r.optional_string("scenario");
  f.workflow = r.optional_string("workflow");
  f.platform = r.optional_string("platform");
  f.files_host = r.optional_string("files_host");
  f.hosts = r.strings("hosts");
  f.profile = r.string("profile", "");
  if (!f.profile.empty() && f.profile != "paper" && f.profile != "linux") r.fail("profile", "expected \"paper\" or \"linux\"");
  f.axes = r.tables("axes");
  f.points = r.tables("points");
  r.finish();
  if (f.scenario && f.workflow) r.fail("workflow", "a sweep's base is a scenario or a workflow, not both");
  if (f.workflow && !f.platform) r.fail("workflow", "a workflow runs on a platform: add platform = \"PLATFORM.xml\"");
  if (!f.workflow && (f.platform || f.files_host || !f.hosts.empty())) {
    r.fail(f.platform ? "platform" : f.files_host ? "files_host" : "hosts", "places a workflow's run: it goes with workflow = \"W.json\"");
  }
  return f;
}

// A scenario TOML naming the workflow, where its files are and the platform it runs on.
std::string workflow_base(const SweepFile& f, const std::string& path) {
  toml::table wf{{"file", absolute_beside(*f.workflow, path)}};
  if (f.files_host) wf.insert("files_host", *f.files_host);
  if (!f.hosts.empty()) {
    toml::array list;
    for (const std::string& h : f.hosts) list.push_back(h);
    wf.insert("hosts", std::move(list));
  }
  const toml::table base{{"platform", absolute_beside(*f.platform, path)}, {"workflow", std::move(wf)}};
  std::ostringstream out;
  out << base;
  return out.str();
}

}  // namespace

std::string run_id(const std::vector<Override>& overrides) {
  std::vector<const Override*> sorted;
  for (const Override& o : overrides)
    if (!o.toml.empty()) sorted.push_back(&o);
  std::sort(sorted.begin(), sorted.end(), [](const Override* a, const Override* b) { return a->key < b->key; });
  std::uint64_t h = kFnvStart;
  for (const Override* o : sorted) h = fnv1a(o->key + "=" + o->toml + "\n", h);
  return hex16(h);
}

Sweep Sweep::load(const std::string& path, bool force, const std::function<void()>& checkpoint) {
  return parse(formats::read_text_file(path, "sweep file"), path, force, {}, checkpoint);
}

Sweep Sweep::parse(const std::string& text, const std::string& path, bool force, const SweepLimits& limits, const std::function<void()>& checkpoint) {
  Sweep plan;
  plan.file_ = fs::absolute(path).lexically_normal().string();
  const toml::table root = parse_toml(text, path);
  scenario::TomlReader r(root, "", path);
  const SweepFile f = read_sweep_file(r);
  plan.profile_ = f.profile;
  if (f.scenario) plan.scenario_ = absolute_beside(*f.scenario, path);
  if (f.workflow) plan.workflow_text_ = workflow_base(f, path);
  if (f.axes.empty() == f.points.empty()) r.fail_table("a sweep has [[axes]] (a grid) or [[points]] (a list of runs), one of them");

  const std::vector<AxisShape> grid = read_axes(f.axes, path, limits);
  check_run_count(grid, f.points.size(), force, limits, path);
  std::vector<std::pair<std::size_t, std::string>> to_check;  // (axis, where) of the values to try on the base
  for (std::size_t i = 0; i < grid.size(); ++i) {
    std::vector<Override> values = axis_values(grid[i], *f.axes[i], i, path);
    plan.keys_.push_back(grid[i].key);
    plan.axes_.push_back(std::move(values));
    to_check.emplace_back(i, grid[i].name);
  }
  if (!f.points.empty()) plan.points_ = read_points(f.points, plan.keys_, path);
  // The grid as made: a log range of integers may have merged values that round alike.
  std::size_t size = plan.points_.size();
  if (plan.points_.empty()) {
    size = 1;
    for (const auto& values : plan.axes_) size *= values.size();
  }
  plan.size_ = size;
  plan.check_values(to_check, limits.scenario, checkpoint);
  for (std::size_t i = 0; i < plan.points_.size(); ++i) {
    if (checkpoint) checkpoint();
    try {
      std::vector<std::pair<std::string, std::string>> overrides;
      for (const Override& o : plan.points_[i])
        if (!o.toml.empty()) overrides.emplace_back(o.key, o.toml);
      plan.load_base(overrides, limits.scenario);
    } catch (const ConfigError& e) {
      fail_at(*f.points[i], path, fmt::format("points[{}]: {}", i, e.what()));
    }
  }
  plan.base_ = identify_base(plan.scenario_, plan.workflow_text_, plan.profile_);
  plan.fingerprint_ = plan.base_.fingerprint();
  return plan;
}

std::size_t Sweep::values_held() const noexcept {
  std::size_t n = 0;
  for (const auto& values : axes_) n += values.size();
  for (const auto& point : points_) n += point.size();
  return n;
}

// Each value of each axis on the base alone, so that a value of the wrong type for its key is
// refused before any run, naming its axis. A range's values share one type: its ends stand
// for it.
void Sweep::check_values(const std::vector<std::pair<std::size_t, std::string>>& where, const ScenarioLimits& limits,
                        const std::function<void()>& checkpoint) const {
  for (const auto& [axis, name] : where) {
    const std::vector<Override>& values = axes_[axis];
    std::vector<const Override*> tried;
    if (values.size() <= 64) {
      for (const Override& v : values) tried.push_back(&v);
    } else {
      tried = {&values.front(), &values.back()};
    }
    for (const Override* v : tried) {
      if (checkpoint) checkpoint();
      try {
        load_base({{v->key, v->toml}}, limits);
      } catch (const ConfigError& e) {
        throw ConfigError(fmt::format("{}: {}, value {}: {}", file_, name, v->toml, e.what()));
      }
    }
  }
}

Run Sweep::run(std::size_t index) const {
  Run run;
  run.index = index;
  if (!points_.empty()) {
    run.overrides = points_.at(index);
  } else {
    // The last axis varies fastest.
    run.overrides.resize(axes_.size());
    std::size_t rest = index;
    for (std::size_t i = axes_.size(); i-- > 0;) {
      run.overrides[i] = axes_[i][rest % axes_[i].size()];
      rest /= axes_[i].size();
    }
  }
  run.id = run_id(run.overrides);
  return run;
}

std::optional<std::size_t> Sweep::index_of(const std::vector<std::pair<std::string, std::string>>& overrides) const {
  const auto value_of = [&](const std::string& key) -> std::string {
    for (const auto& [k, v] : overrides)
      if (k == key) return v;
    return {};
  };
  std::size_t set = 0;
  for (const auto& [key, value] : overrides) set += std::find(keys_.begin(), keys_.end(), key) != keys_.end() && !value.empty() ? 1 : 0;
  if (set != overrides.size()) return std::nullopt;  // a key this plan does not sweep
  if (!points_.empty()) {
    for (std::size_t p = 0; p < points_.size(); ++p) {
      bool same = true;
      for (std::size_t k = 0; k < keys_.size() && same; ++k) same = points_[p][k].toml == value_of(keys_[k]);
      if (same) return p;
    }
    return std::nullopt;
  }
  // The first axis varies slowest.
  std::size_t index = 0;
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    const std::string value = value_of(keys_[k]);
    const auto at = std::find_if(axes_[k].begin(), axes_[k].end(), [&](const Override& o) { return o.toml == value; });
    if (at == axes_[k].end()) return std::nullopt;
    index = index * axes_[k].size() + static_cast<std::size_t>(at - axes_[k].begin());
  }
  return index;
}

Scenario Sweep::load_base(const std::vector<std::pair<std::string, std::string>>& overrides, const ScenarioLimits& limits) const {
  if (!scenario_.empty()) return load_scenario(scenario_, overrides, profile_, limits);
  if (!workflow_text_.empty()) return parse_scenario(workflow_text_, file_, overrides, profile_, limits);
  return parse_scenario(default_scenario_text(), "<embedded default>", overrides, profile_, limits);
}

Scenario Sweep::scenario(const Run& run) const {
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const Override& o : run.overrides)
    if (!o.toml.empty()) overrides.emplace_back(o.key, o.toml);
  return load_base(overrides);
}

std::string Sweep::base_description() const {
  if (!scenario_.empty()) return scenario_;
  if (!workflow_text_.empty()) return "the workflow of " + file_;
  return "<embedded default>";
}

std::string Sweep::json() const {
  std::string out = fmt::format("{{\"sweep\": {}, \"scenario\": {}, \"workflow\": {}, \"profile\": {},\n \"base\": {{\"fingerprint\": \"{}\", \"settings\": {}, \"files\": [",
                                text::json_string(file_), text::json_string(scenario_), text::json_string(workflow_text_), text::json_string(profile_),
                                fingerprint_, text::json_string(base_.settings));
  for (std::size_t i = 0; i < base_.files.size(); ++i) {
    const BaseFile& f = base_.files[i];
    out += fmt::format("{}[{}, {}, \"{}\"]", i ? ", " : "", text::json_string(f.role), text::json_string(f.path), f.hash);
  }
  out += fmt::format("]}},\n \"runs\": {}, \"keys\": [", size_);
  for (std::size_t i = 0; i < keys_.size(); ++i) out += (i ? ", " : "") + text::json_string(keys_[i]);
  out += "],\n \"axes\": [";
  // Each value as [TOML text, as shown]; an unset key of a point as [].
  const auto values = [](const std::vector<Override>& list) {
    std::string s = "[";
    for (std::size_t i = 0; i < list.size(); ++i) {
      s += i ? ", " : "";
      s += list[i].toml.empty() ? "[]" : fmt::format("[{}, {}]", text::json_string(list[i].toml), text::json_string(list[i].shown));
    }
    return s + "]";
  };
  for (std::size_t i = 0; i < axes_.size(); ++i) out += (i ? ",\n  " : "\n  ") + values(axes_[i]);
  out += "],\n \"points\": [";
  for (std::size_t i = 0; i < points_.size(); ++i) out += (i ? ",\n  " : "\n  ") + values(points_[i]);
  return out + "]}\n";
}

Sweep Sweep::from_json(const std::string& text, const std::string& origin) {
  Sweep plan;
  try {
    const nlohmann::json doc = nlohmann::json::parse(text);
    formats::check_unique_keys(text, origin);
    plan.file_ = doc.at("sweep").get<std::string>();
    plan.scenario_ = doc.at("scenario").get<std::string>();
    plan.workflow_text_ = doc.at("workflow").get<std::string>();
    plan.profile_ = doc.at("profile").get<std::string>();
    if (!doc.contains("base")) {
      throw ConfigError(fmt::format("{}: the plan of a sweep run by an earlier pcsim, which did not record its base's fingerprint: merge it with "
                                    "that pcsim, or run the sweep again into another folder", origin));
    }
    const nlohmann::json& base = doc.at("base");
    plan.base_.settings = base.at("settings").get<std::string>();
    for (const nlohmann::json& f : base.at("files")) {
      plan.base_.files.push_back({f.at(0).get<std::string>(), f.at(1).get<std::string>(), f.at(2).get<std::string>()});
      if (f.size() != 3 || !is_hex16(plan.base_.files.back().hash)) throw ConfigError(fmt::format("{}: not a sweep plan pcsim wrote (a base file)", origin));
    }
    plan.fingerprint_ = base.at("fingerprint").get<std::string>();
    if (plan.fingerprint_ != plan.base_.fingerprint()) throw ConfigError(fmt::format("{}: a sweep plan whose base does not add up", origin));
    plan.size_ = doc.at("runs").get<std::size_t>();
    plan.keys_ = doc.at("keys").get<std::vector<std::string>>();
    const auto list = [&](const nlohmann::json& values) {
      std::vector<Override> out;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const nlohmann::json& v = values.at(i);
        if (v.empty()) out.emplace_back();
        else out.push_back({std::string(), v.at(0).get<std::string>(), v.at(1).get<std::string>()});  // keys set below
      }
      return out;
    };
    for (std::size_t i = 0; i < doc.at("axes").size(); ++i) {
      plan.axes_.push_back(list(doc["axes"][i]));
      for (Override& o : plan.axes_.back()) o.key = plan.keys_.at(i);
    }
    for (const nlohmann::json& p : doc.at("points")) {
      plan.points_.push_back(list(p));
      for (std::size_t k = 0; k < plan.points_.back().size(); ++k) plan.points_.back()[k].key = plan.keys_.at(k);
    }
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError(fmt::format("{}: not a sweep plan pcsim wrote ({})", origin, e.what()));
  }
  std::size_t expected = plan.points_.size();
  if (!plan.axes_.empty()) {
    expected = 1;
    for (const auto& a : plan.axes_) expected *= a.size();
  }
  if (expected != plan.size_ || (plan.axes_.empty() && plan.points_.empty())) throw ConfigError(fmt::format("{}: a sweep plan that does not add up", origin));
  return plan;
}

}  // namespace pagecache::sweep
