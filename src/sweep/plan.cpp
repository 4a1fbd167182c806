#include "sweep/plan.hpp"

#include "scenario/text_file.hpp"
#include "scenario/toml_reader.hpp"
#include "text/json_string.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

namespace pagecache::sweep {

namespace {

namespace fs = std::filesystem;
using scenario::location;

[[noreturn]] void fail_at(const toml::node& node, const std::string& file, const std::string& what) {
  throw ConfigError(fmt::format("{}: {}", location(node.source(), file), what));
}

// A float as TOML text that reads back as the same float: 12 significant digits drop the
// residue of from + k * step (0.30000000000000004 is 0.3).
std::string float_text(double v) {
  std::string s = fmt::format("{:.12g}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
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

// range = { from, to, step } or { from, to, factor }: the values from `from` up to `to`.
std::vector<Override> range_values(const std::string& key, const toml::table& range, const std::string& file, const std::string& where) {
  scenario::TomlReader r(range, where + ".range", file);
  const toml::node* from = r.raw("from");
  const toml::node* to = r.raw("to");
  const toml::node* step = r.raw("step");
  const toml::node* factor = r.raw("factor");
  r.finish();
  if (from == nullptr || to == nullptr) r.fail_table("a range needs from and to, and step or factor");
  if ((step == nullptr) == (factor == nullptr)) r.fail_table("a range has a step or a factor (a log range), one of them");
  const toml::node& by = step != nullptr ? *step : *factor;
  for (const toml::node* n : {from, to, &by}) {
    if (!n->is_number()) fail_at(*n, file, fmt::format("{}: from, to, step and factor are numbers", where));
  }
  const bool integers = from->is_integer() && to->is_integer() && by.is_integer();
  const double a = *from->value<double>(), b = *to->value<double>(), s = *by.value<double>();
  const auto text = [&](double v) { return integers ? fmt::format("{}", static_cast<std::int64_t>(std::llround(v))) : float_text(v); };
  std::vector<Override> out;
  constexpr double kMaxValues = 1e7;
  if (step != nullptr) {
    if (!(s != 0.0) || !std::isfinite(s)) fail_at(by, file, fmt::format("{}: the step cannot be 0", where));
    const double n = std::floor((b - a) / s * (1.0 + 1e-12)) + 1.0;
    if (!(n >= 1.0)) fail_at(by, file, fmt::format("{}: from {} the step {} never reaches {}", where, a, s, b));
    if (n > kMaxValues) fail_at(by, file, fmt::format("{}: {:.0f} values, more than an axis may have ({:.0f})", where, n, kMaxValues));
    for (double k = 0; k < n; ++k) out.push_back({key, text(a + k * s), text(a + k * s)});
  } else {
    const bool up = s > 1.0 && a > 0.0 && b >= a;
    const bool down = s > 0.0 && s < 1.0 && b > 0.0 && a >= b;
    if (!up && !down) fail_at(by, file, fmt::format("{}: a factor range needs 0 < from <= to with factor > 1, or from >= to > 0 with 0 < factor < 1", where));
    double v = a;
    for (double k = 0; up ? v <= b * (1.0 + 1e-12) : v >= b * (1.0 - 1e-12); ++k, v = a * std::pow(s, k)) {
      if (k >= kMaxValues) fail_at(by, file, fmt::format("{}: more values than an axis may have ({:.0f})", where, kMaxValues));
      if (!out.empty() && out.back().toml == text(v)) continue;  // integers: a factor below 2 can round to the same value
      out.push_back({key, text(v), text(v)});
    }
  }
  return out;
}

std::string absolute_beside(const std::string& path, const std::string& file) {
  const fs::path p(path);
  return (p.is_absolute() ? p : fs::absolute(fs::path(file).parent_path() / p)).lexically_normal().string();
}

std::uint64_t fnv1a(std::string_view text, std::uint64_t h = 0xcbf29ce484222325ULL) {
  for (const unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

}  // namespace

std::string run_id(const std::vector<Override>& overrides) {
  std::vector<const Override*> sorted;
  for (const Override& o : overrides)
    if (!o.toml.empty()) sorted.push_back(&o);
  std::sort(sorted.begin(), sorted.end(), [](const Override* a, const Override* b) { return a->key < b->key; });
  std::uint64_t h = fnv1a("");
  for (const Override* o : sorted) h = fnv1a(o->key + "=" + o->toml + "\n", h);
  return fmt::format("{:016x}", h);
}

Plan Plan::load(const std::string& path, bool force) {
  Plan plan;
  plan.file_ = fs::absolute(path).lexically_normal().string();
  const std::string text = scenario::read_text_file(path, "sweep file");
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

  std::vector<std::pair<std::size_t, std::string>> to_check;  // (axis, where) of the values to try on the base
  double runs = 1.0;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const std::string where = fmt::format("axes[{}]", i);
    scenario::TomlReader a(*axes[i], where, path);
    const std::string key = a.required_string("key");
    const toml::node* values = a.raw("values");
    const toml::table* range = a.optional_table("range");
    a.finish();
    const std::string axis = fmt::format("axis '{}'", key);
    if (std::find(plan.keys_.begin(), plan.keys_.end(), key) != plan.keys_.end()) a.fail("key", fmt::format("{} is swept twice", axis));
    if ((values == nullptr) == (range == nullptr)) a.fail_table(fmt::format("{}: give values = [...] or range = {{...}}, one of them", axis));
    std::vector<Override> list;
    if (values != nullptr) {
      const toml::array* array = values->as_array();
      if (array == nullptr) a.fail("values", fmt::format("{}: expected an array of values", axis));
      for (const toml::node& v : *array) list.push_back(override_of(key, v, path, axis));
    } else {
      list = range_values(key, *range, path, axis);
    }
    if (list.empty()) a.fail("values", fmt::format("{} has no value", axis));
    std::set<std::string> seen;
    for (const Override& o : list) {
      if (!seen.insert(o.toml).second) a.fail(values ? "values" : "range", fmt::format("{}: the value {} is there twice", axis, o.toml));
    }
    runs *= static_cast<double>(list.size());
    plan.keys_.push_back(key);
    plan.axes_.push_back(std::move(list));
    to_check.emplace_back(i, axis);
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
    runs = static_cast<double>(rows.size());
    plan.points_ = std::move(rows);
  }
  if (runs > kMaxRuns && !force) {
    std::string shape;
    for (std::size_t i = 0; i < plan.axes_.size(); ++i) shape += fmt::format("{}axis '{}' {}", i ? " x " : "", plan.keys_[i], plan.axes_[i].size());
    throw ConfigError(fmt::format("{}: {:.0f} runs ({}), more than {:.0f}: give --force to sweep them all", path, runs, shape, kMaxRuns));
  }
  if (runs > 1e12) throw ConfigError(fmt::format("{}: {:.3g} runs, more than pcsim can number", path, runs));
  plan.size_ = static_cast<std::size_t>(runs);
  plan.check_values(to_check);
  if (!plan.points_.empty()) {
    for (std::size_t i = 0; i < plan.points_.size(); ++i) {
      try {
        plan.scenario(plan.run(i));
      } catch (const ConfigError& e) {
        fail_at(*points[i], path, fmt::format("points[{}]: {}", i, e.what()));
      }
    }
  }
  return plan;
}

// Each value of each axis on the base alone, so that a value of the wrong type for its key is
// refused before any run, naming its axis. A range's values share one type: its ends stand
// for it.
void Plan::check_values(const std::vector<std::pair<std::size_t, std::string>>& where) const {
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
        load_base({{v->key, v->toml}});
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

Scenario Plan::load_base(const std::vector<std::pair<std::string, std::string>>& overrides) const {
  if (!scenario_.empty()) return load_scenario(scenario_, overrides, profile_);
  if (!workflow_text_.empty()) return parse_scenario(workflow_text_, file_, overrides, profile_);
  return parse_scenario(default_scenario_text(), "<embedded default>", overrides, profile_);
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
  std::string out = fmt::format("{{\"sweep\": {}, \"scenario\": {}, \"workflow\": {}, \"profile\": {}, \"runs\": {}, \"keys\": [", text::json_string(file_),
                                text::json_string(scenario_), text::json_string(workflow_text_), text::json_string(profile_), size_);
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
