#include "sweep/plan.hpp"

#include "scenario/text_file.hpp"
#include "scenario/toml_reader.hpp"
#include "sweep/hash.hpp"
#include "sweep/range.hpp"
#include "text/json_string.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;
using scenario::location;

[[noreturn]] void fail_at(const toml::node& node, const std::string& file, const std::string& what) {
  throw ConfigError(fmt::format("{}: {}", location(node.source(), file), what));
}

// A value of an axis or a point as an override.
Override override_of(const std::string& key, const toml::node& value, const std::string& file, const std::string& where) {
  std::ostringstream text;
  std::string shown;
  if (const auto* s = value.as_string()) {
    shown = s->get();
    text << '"';  // a basic string: toml++ would write a literal one ('64 GB')
    for (const char c : shown) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') text << '\\' << c;
      else if (byte < 0x20 || byte == 0x7f) text << fmt::format("\\u{:04X}", byte);
      else text << c;
    }
    text << '"';
  } else if (const auto* f = value.as_floating_point()) {
    text << float_text(f->get());  // toml++ writes 0.2 as 0.20000000000000001
    shown = text.str();
  } else if (value.is_integer() || value.is_boolean()) {
    value.visit([&](const auto& v) {
      if constexpr (toml::is_value<decltype(v)>) text << v;
    });
    shown = text.str();
  } else {
    fail_at(value, file, fmt::format("{}: a value is a string, a number or true/false", where));
  }
  return {key, text.str(), shown};
}

std::string absolute_beside(const std::string& path, const std::string& file) {
  const fs::path p(path);
  return (p.is_absolute() ? p : fs::absolute(fs::path(file).parent_path() / p)).lexically_normal().string();
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

Plan Plan::load(const std::string& path, bool force) { return parse(scenario::read_text_file(path, "sweep file"), path, force); }

Plan Plan::parse(const std::string& text, const std::string& path, bool force, const PlanLimits& limits) {
  Plan plan;
  plan.file_ = fs::absolute(path).lexically_normal().string();
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}: {}", location(e.source(), path), e.description()));
  }
  scenario::TomlReader r(root, "", path);
  const auto scenario = r.optional_string("scenario");
  const auto workflow = r.optional_string("workflow");
  const auto platform = r.optional_string("platform");
  const auto files_host = r.optional_string("files_host");
  const std::vector<std::string> hosts = r.strings("hosts");
  plan.profile_ = r.string("profile", "");
  if (!plan.profile_.empty() && plan.profile_ != "paper" && plan.profile_ != "linux") r.fail("profile", "expected \"paper\" or \"linux\"");
  const std::vector<const toml::table*> axes = r.tables("axes");
  const std::vector<const toml::table*> points = r.tables("points");
  r.finish();
  if (scenario && workflow) r.fail("workflow", "a sweep's base is a scenario or a workflow, not both");
  if (workflow && !platform) r.fail("workflow", "a workflow runs on a platform: add platform = \"PLATFORM.xml\"");
  if (!workflow && (platform || files_host || !hosts.empty())) {
    r.fail(platform ? "platform" : files_host ? "files_host" : "hosts", "places a workflow's run: it goes with workflow = \"W.json\"");
  }
  if (scenario) plan.scenario_ = absolute_beside(*scenario, path);
  if (workflow) {
    toml::table wf{{"file", absolute_beside(*workflow, path)}};
    if (files_host) wf.insert("files_host", *files_host);
    if (!hosts.empty()) {
      toml::array list;
      for (const std::string& h : hosts) list.push_back(h);
      wf.insert("hosts", std::move(list));
    }
    const toml::table base{{"platform", absolute_beside(*platform, path)}, {"workflow", std::move(wf)}};
    std::ostringstream out;
    out << base;
    plan.workflow_text_ = out.str();
  }
  if (axes.empty() == points.empty()) r.fail_table("a sweep has [[axes]] (a grid) or [[points]] (a list of runs), one of them");

  // First each axis's length, and the grid's, without making a value: a range of 10^9 values
  // is refused at once, not once it has filled the memory.
  struct Axis {
    std::string key, name;
    const toml::array* values = nullptr;
    std::optional<Range> range;
    double length = 0;
  };
  std::vector<Axis> grid;
  double runs = 1.0;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    scenario::TomlReader a(*axes[i], fmt::format("axes[{}]", i), path);
    Axis axis;
    axis.key = a.required_string("key");
    const toml::node* values = a.raw("values");
    const toml::table* range = a.optional_table("range");
    a.finish();
    axis.name = fmt::format("axis '{}'", axis.key);
    for (const Axis& earlier : grid)
      if (earlier.key == axis.key) a.fail("key", fmt::format("{} is swept twice", axis.name));
    if ((values == nullptr) == (range == nullptr)) a.fail_table(fmt::format("{}: give values = [...] or range = {{...}}, one of them", axis.name));
    if (values != nullptr) {
      axis.values = values->as_array();
      if (axis.values == nullptr) a.fail("values", fmt::format("{}: expected an array of values", axis.name));
      axis.length = static_cast<double>(axis.values->size());
      if (axis.length == 0) a.fail("values", fmt::format("{} has no value", axis.name));
      if (axis.length > limits.axis_values) {
        a.fail("values", fmt::format("{}: {} values, more than an axis may have ({:.0f})", axis.name, axis.values->size(), limits.axis_values));
      }
    } else {
      axis.range = read_range(axis.key, *range, path, axis.name);
      axis.length = range_length(*axis.range, limits.axis_values);
    }
    runs *= axis.length;
    grid.push_back(std::move(axis));
  }
  if (!points.empty()) runs = static_cast<double>(points.size());
  const double allowed = force ? kMaxNumberedRuns : limits.runs;
  if (runs > allowed) {
    if (runs > kMaxNumberedRuns) throw ConfigError(fmt::format("{}: {:.3g} runs, more than pcsim can number", path, runs));
    std::string shape;
    for (std::size_t i = 0; i < grid.size(); ++i) shape += fmt::format("{}{} {:.0f}", i ? " x " : "", grid[i].name, grid[i].length);
    if (shape.empty()) shape = "points";
    throw ConfigError(fmt::format("{}: {:.0f} runs ({}), more than {:.0f}: give --force to sweep them all", path, runs, shape, allowed));
  }

  std::vector<std::pair<std::size_t, std::string>> to_check;  // (axis, where) of the values to try on the base
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Axis& axis = grid[i];
    std::vector<Override> list;
    if (axis.values != nullptr) {
      list.reserve(axis.values->size());
      for (const toml::node& v : *axis.values) list.push_back(override_of(axis.key, v, path, axis.name));
    } else {
      list = range_values(*axis.range);
    }
    std::set<std::string> seen;
    for (const Override& o : list) {
      if (!seen.insert(o.toml).second) {
        scenario::TomlReader(*axes[i], fmt::format("axes[{}]", i), path)
            .fail(axis.values != nullptr ? "values" : "range", fmt::format("{}: the value {} is there twice", axis.name, o.toml));
      }
    }
    plan.keys_.push_back(axis.key);
    plan.axes_.push_back(std::move(list));
    to_check.emplace_back(i, axis.name);
  }
  if (!points.empty()) {
    // Keys in the order they first appear; a point leaves unset what it does not name.
    std::vector<std::vector<Override>> rows;
    for (std::size_t i = 0; i < points.size(); ++i) {
      std::vector<Override> row(plan.keys_.size());
      for (const auto& [k, v] : *points[i]) {
        const std::string key(k.str());
        auto at = std::find(plan.keys_.begin(), plan.keys_.end(), key);
        if (at == plan.keys_.end()) {
          plan.keys_.push_back(key);
          for (auto& earlier : rows) earlier.emplace_back();
          row.emplace_back();
          at = plan.keys_.end() - 1;
        }
        row[static_cast<std::size_t>(at - plan.keys_.begin())] = override_of(key, v, path, fmt::format("points[{}], key '{}'", i, key));
      }
      rows.push_back(std::move(row));
    }
    std::set<std::string> ids;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!ids.insert(run_id(rows[i])).second) fail_at(*points[i], path, fmt::format("points[{}] is the same run as an earlier point", i));
    }
    plan.points_ = std::move(rows);
  }
  // The grid as made: a log range of integers may have merged values that round alike.
  std::size_t size = plan.points_.size();
  if (plan.points_.empty()) {
    size = 1;
    for (const auto& values : plan.axes_) size *= values.size();
  }
  plan.size_ = size;
  plan.check_values(to_check, limits.scenario);
  if (!plan.points_.empty()) {
    for (std::size_t i = 0; i < plan.points_.size(); ++i) {
      try {
        std::vector<std::pair<std::string, std::string>> overrides;
        for (const Override& o : plan.points_[i])
          if (!o.toml.empty()) overrides.emplace_back(o.key, o.toml);
        plan.load_base(overrides, limits.scenario);
      } catch (const ConfigError& e) {
        fail_at(*points[i], path, fmt::format("points[{}]: {}", i, e.what()));
      }
    }
  }
  plan.base_ = identify_base(plan.scenario_, plan.workflow_text_, plan.profile_);
  plan.fingerprint_ = plan.base_.fingerprint();
  return plan;
}

std::size_t Plan::values_held() const noexcept {
  std::size_t n = 0;
  for (const auto& values : axes_) n += values.size();
  for (const auto& point : points_) n += point.size();
  return n;
}

// Each value of each axis on the base alone, so that a value of the wrong type for its key is
// refused before any run, naming its axis. A range's values share one type: its ends stand
// for it.
void Plan::check_values(const std::vector<std::pair<std::size_t, std::string>>& where, const ScenarioLimits& limits) const {
  for (const auto& [axis, name] : where) {
    const std::vector<Override>& values = axes_[axis];
    std::vector<const Override*> tried;
    if (values.size() <= 64) {
      for (const Override& v : values) tried.push_back(&v);
    } else {
      tried = {&values.front(), &values.back()};
    }
    for (const Override* v : tried) {
      try {
        load_base({{v->key, v->toml}}, limits);
      } catch (const ConfigError& e) {
        throw ConfigError(fmt::format("{}: {}, value {}: {}", file_, name, v->toml, e.what()));
      }
    }
  }
}

Run Plan::run(std::size_t index) const {
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

Scenario Plan::load_base(const std::vector<std::pair<std::string, std::string>>& overrides, const ScenarioLimits& limits) const {
  if (!scenario_.empty()) return load_scenario(scenario_, overrides, profile_, limits);
  if (!workflow_text_.empty()) return parse_scenario(workflow_text_, file_, overrides, profile_, limits);
  return parse_scenario(default_scenario_text(), "<embedded default>", overrides, profile_, limits);
}

Scenario Plan::scenario(const Run& run) const {
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const Override& o : run.overrides)
    if (!o.toml.empty()) overrides.emplace_back(o.key, o.toml);
  return load_base(overrides);
}

std::string Plan::base_description() const {
  if (!scenario_.empty()) return scenario_;
  if (!workflow_text_.empty()) return "the workflow of " + file_;
  return "<embedded default>";
}

std::string Plan::json() const {
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

Plan Plan::from_json(const std::string& text, const std::string& origin) {
  Plan plan;
  try {
    const nlohmann::json doc = nlohmann::json::parse(text);
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
