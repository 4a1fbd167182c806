#include "sweep/result_line.hpp"

#include "sweep/hash.hpp"
#include "text/json_string.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <set>
#include <vector>

namespace pagecache::sweep {

std::string result_line(const std::string& fingerprint, const Run& run, const RunResult* result, int exit_code, const std::string& error,
                        double wall) {
  std::string out = fmt::format("{{\"id\": \"{}\", \"base\": \"{}\", \"run\": {}, \"overrides\": {{", run.id, fingerprint, run.index);
  bool first = true;
  for (const Override& o : run.overrides) {
    if (o.toml.empty()) continue;
    out += fmt::format("{}{}: {}", first ? "" : ", ", text::json_string(o.key), text::json_string(o.toml));
    first = false;
  }
  out += "}, ";
  if (result == nullptr) {
    out += fmt::format("\"status\": \"failed\", \"exit_code\": {}, \"error\": {}", exit_code, text::json_string(error));
  } else {
    // In kResultFigures' order.
    const RunSummary& s = result->summary;
    out += fmt::format(
        "\"status\": \"ok\", \"exit_code\": 0, \"makespan_s\": {:.6f}, \"end_time_s\": {:.6f}, \"read_s\": {:.6f}, \"compute_s\": {:.6f}, "
        "\"write_s\": {:.6f}, \"disk_read_bytes\": {}, \"cache_read_bytes\": {}, \"forced_flush_bytes\": {}, \"periodic_flush_bytes\": {}, "
        "\"evicted_bytes\": {}, \"peak_dirty_bytes\": {}, \"events\": {}",
        s.makespan, s.end_time, s.read.seconds, s.compute.seconds, s.write.seconds, s.disk_read_bytes, s.cache_read_bytes, s.forced_flush_bytes,
        s.periodic_flush_bytes, s.evicted_bytes, s.peak_dirty_bytes, s.events);
  }
  return out + fmt::format(", \"wall_s\": {:.6f}, \"sim_wall_s\": {:.6f}}}", wall, result != nullptr ? result->summary.wall_seconds : 0.0);
}

namespace {

// What a member's value is, as result_line writes it.
enum class Kind { Id, Base, Index, Overrides, Status, ExitCode, Seconds, Count, Error };

struct Member {
  const char* key;
  Kind kind;
};

constexpr Member kHead[] = {{"id", Kind::Id},           {"base", Kind::Base},     {"run", Kind::Index},
                            {"overrides", Kind::Overrides}, {"status", Kind::Status}, {"exit_code", Kind::ExitCode}};
constexpr Member kTail[] = {{"wall_s", Kind::Seconds}, {"sim_wall_s", Kind::Seconds}};

// A string of the line as a message shows it: quoted, escaped, at most 40 bytes of it.
std::string in_message(std::string_view text) { return text::json_string(text.substr(0, 40)) + (text.size() > 40 ? "..." : ""); }

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::Id:
    case Kind::Base: return "16 hex digits";
    case Kind::Index:
    case Kind::Count: return "a whole number";
    case Kind::Overrides: return "an object of strings";
    case Kind::Status: return "\"ok\" or \"failed\"";
    case Kind::ExitCode: return "an exit code";
    case Kind::Seconds: return "seconds, a number with a fraction";
    case Kind::Error: return "a string";
  }
  return "";
}

// Follows the parser's events through a line, against the members result_line writes in its
// order; stops at the first that differs. Each override is kept, to check the id against.
class Shape final : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit Shape(std::string_view fingerprint) : fingerprint_(fingerprint), expected_(std::begin(kHead), std::end(kHead)) {}

  std::string problem;       // empty while the line has pcsim's shape
  bool other_sweep = false;  // its "base" is another fingerprint
  bool whole = false;        // the object closed with every member
  bool cut_number = false;   // the last event: a whole number where pcsim writes seconds (cut before the '.'?)
  std::size_t error_at = 0;  // where the parser stopped (1 + the bytes it read)
  std::string id;
  std::vector<Override> overrides;

  bool null() override { return wrong("null"); }
  bool boolean(bool) override { return wrong("true or false"); }
  bool number_integer(number_integer_t) override { return wrong("a negative number"); }
  bool number_unsigned(number_unsigned_t v) override {
    if (depth_ != 1) return wrong("a number");
    const Kind kind = value_kind();
    if (kind == Kind::Seconds) {
      cut_number = true;  // forgiven only if nothing follows
      return true;
    }
    // The byte counts are int64 in a run's summary, the events uint64.
    if (kind == Kind::Count && key_ != "events" && v > static_cast<number_unsigned_t>(INT64_MAX)) return fail(fmt::format("{} is {}", in_message(key_), v));
    if (kind == Kind::Index || kind == Kind::Count) return done_value();
    if (kind != Kind::ExitCode) return wrong("a number");
    if (status_ == "ok" ? v != 0 : (v < 1 || v > 3)) return fail(fmt::format("exit code {} with status \"{}\"", v, status_));
    return done_value();
  }
  bool number_float(number_float_t v, const string_t&) override {
    if (depth_ != 1 || value_kind() != Kind::Seconds) return wrong("a number with a fraction");
    if (!(v >= 0.0) || !std::isfinite(v)) return fail(fmt::format("{} is {}", in_message(key_), v));
    return done_value();
  }
  bool string(string_t& v) override {
    if (depth_ == 2) {
      if (v.empty()) return fail(fmt::format("the override of {} is empty", in_message(override_key_)));
      overrides.push_back({override_key_, v, {}});
      return true;
    }
    if (depth_ != 1) return wrong("a string");
    switch (value_kind()) {
      case Kind::Id:
        if (!is_hex16(v)) return fail(fmt::format("the id {} is not 16 hex digits", in_message(v)));
        id = v;
        return done_value();
      case Kind::Base:
        if (!is_hex16(v)) return fail(fmt::format("the base {} is not 16 hex digits", in_message(v)));
        if (v != fingerprint_) {
          other_sweep = true;
          return fail(fmt::format("its base is {}, this sweep's {}", v, fingerprint_));
        }
        return done_value();
      case Kind::Status:
        if (v != "ok" && v != "failed") return fail(fmt::format("status {}", in_message(v)));
        status_ = v;
        if (v == "ok") {
          for (const char* figure : kResultFigures) {
            const std::string_view name(figure);
            expected_.push_back({figure, name.size() > 2 && name.substr(name.size() - 2) == "_s" ? Kind::Seconds : Kind::Count});
          }
        } else {
          expected_.push_back({"error", Kind::Error});
        }
        expected_.insert(expected_.end(), std::begin(kTail), std::end(kTail));
        return done_value();
      case Kind::Error: return done_value();
      default: return wrong("a string");
    }
  }
  bool binary(binary_t&) override { return wrong("binary"); }
  bool start_object(std::size_t) override {
    if (depth_ == 0 && !whole) return ++depth_, true;
    if (depth_ == 1 && value_kind() == Kind::Overrides) return ++depth_, true;
    return wrong("an object");
  }
  bool key(string_t& k) override {
    if (!settled()) return false;
    if (depth_ == 2) {
      if (!keys_.insert(k).second) return fail(fmt::format("the override of {} is there twice", in_message(k)));
      override_key_ = k;
      return true;
    }
    if (next_ >= expected_.size()) return fail(fmt::format("{} after {}, pcsim's last member", in_message(k), in_message(key_)));
    if (k != expected_[next_].key) return fail(fmt::format("{} where pcsim writes \"{}\"", in_message(k), expected_[next_].key));
    key_ = k;
    pending_ = true;
    ++next_;
    return true;
  }
  bool end_object() override {
    if (!settled()) return false;
    if (depth_ == 2) {
      --depth_;
      return done_value();
    }
    if (next_ < expected_.size()) return fail(fmt::format("it ends where pcsim writes \"{}\"", expected_[next_].key));
    --depth_;
    whole = true;
    return true;
  }
  bool start_array(std::size_t) override { return wrong("an array"); }
  bool end_array() override { return wrong("an array"); }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception&) override {
    error_at = position;
    return false;
  }

 private:
  Kind value_kind() const { return pending_ ? expected_[next_ - 1].kind : Kind::Error; }
  bool done_value() {
    pending_ = false;
    return true;
  }
  // A whole number where seconds go is forgiven only as the line's last token.
  bool settled() {
    if (!cut_number) return true;
    cut_number = false;
    return wrong("a whole number");
  }
  bool wrong(const char* what) {
    if (!pending_ && depth_ != 2) return fail(fmt::format("{} where pcsim writes no value", what));
    if (depth_ == 2) return fail(fmt::format("{} in the overrides, where pcsim writes strings", what));
    return fail(fmt::format("{} is {}, not {}", in_message(key_), what, kind_name(value_kind())));
  }
  bool fail(std::string why) {
    if (problem.empty()) problem = std::move(why);
    return false;
  }

  std::string fingerprint_;
  std::vector<Member> expected_;
  std::size_t next_ = 0;  // in expected_
  bool pending_ = false;  // a member's key read, its value not yet
  int depth_ = 0;
  std::string key_, override_key_, status_;
  std::set<std::string> keys_;
};

std::string not_pcsim(const Shape& shape, std::string_view fallback) {
  if (shape.other_sweep) return "the result of a run of another sweep (" + shape.problem + ": copied from another sweep's folder?)";
  return fmt::format("not a result pcsim wrote ({})", shape.problem.empty() ? fallback : shape.problem);
}

}  // namespace

LineCheck check_result_line(std::string_view line, std::string_view fingerprint) {
  // pcsim writes no space around a line's object, which JSON would allow, and no NUL byte,
  // which nlohmann's parser takes for the end of the input.
  if (line.empty() || line.front() != '{' || line.back() != '}' || line.find('\0') != std::string_view::npos) {
    return {{}, "not a result pcsim wrote (not one JSON object)"};
  }
  Shape shape(fingerprint);
  const bool parsed = nlohmann::json::sax_parse(line.begin(), line.end(), &shape);
  if (!parsed || !shape.problem.empty() || !shape.whole) return {{}, not_pcsim(shape, "not one JSON object")};
  if (const std::string made = run_id(shape.overrides); made != shape.id) {
    return {{}, fmt::format("not a result pcsim wrote (its id {} is not that of its overrides, {})", shape.id, made)};
  }
  return {shape.id, {}};
}

LineCheck check_cut_result_line(std::string_view partial, std::string_view fingerprint) {
  if (partial.empty() || partial.front() != '{' || partial.find('\0') != std::string_view::npos) {
    return {{}, "not a result pcsim wrote (not the beginning of a JSON object)"};
  }
  Shape shape(fingerprint);
  if (nlohmann::json::sax_parse(partial.begin(), partial.end(), &shape)) return check_result_line(partial, fingerprint);
  // Cut short, the parser stops at the end of the bytes, 1 past them, not before.
  if (!shape.problem.empty()) return {{}, not_pcsim(shape, "")};
  if (shape.error_at != partial.size() + 1) return {{}, "not a result pcsim wrote (not the beginning of a JSON object)"};
  if (shape.cut_number && (partial.back() < '0' || partial.back() > '9')) return {{}, not_pcsim(shape, "a whole number")};
  return {shape.id, {}};
}

}  // namespace pagecache::sweep
