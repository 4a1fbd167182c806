#include "formats/fio/options.hpp"

#include "formats/common/closest.hpp"
#include "formats/fio/values.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string_view>

namespace pagecache::formats::fio {

namespace {

using Setter = void (*)(Draft&, const RawOption&, Warnings&);

struct Supported {
  std::string_view name;
  std::string_view alias;
  Setter set;
};

constexpr std::int64_t kMaxBlock = std::int64_t{2} << 30;
constexpr std::int64_t kMaxUint32 = 0xffffffffLL;

std::string required_text(const RawOption& o) {
  if (o.bare || o.value.empty()) fail(o, fmt::format("option '{}' needs a value", o.key));
  return o.value;
}

std::int64_t single_size(const Draft& d, const RawOption& o) {
  require_single_value(o);
  return parse_size(o, o.value, d.kb_base);
}

SizeOrPercent single_size_or_percent(const Draft& d, const RawOption& o) {
  require_single_value(o);
  return parse_size_or_percent(o, o.value, d.kb_base);
}

// The ":N" count of rw's random modes and of file_service_type, as fio's atoi would read it but
// refusing what atoi would turn into 0 or a wrong number.
std::int64_t io_count(const RawOption& o, const std::string& step) {
  if (step.empty() || step.size() > 9 || step.find_first_not_of("0123456789") != std::string::npos || std::stoll(step) < 1) {
    fail(o, fmt::format("{}: ':N' is a whole number of I/Os, at least 1", label(o)));
  }
  return std::stoll(step);
}

// Random modes first: the :N suffix means a count for them, a byte step for the others.
void set_rw(Draft& d, const RawOption& o, Warnings&) {
  const std::string value = required_text(o);
  const std::size_t colon = value.find(':');
  const std::string mode = value.substr(0, colon);
  static constexpr std::array<std::pair<std::string_view, FioRw>, 7> kModes{{{"randread", FioRw::RandRead},
                                                                            {"randwrite", FioRw::RandWrite},
                                                                            {"randrw", FioRw::RandReadWrite},
                                                                            {"read", FioRw::Read},
                                                                            {"write", FioRw::Write},
                                                                            {"rw", FioRw::ReadWrite},
                                                                            {"readwrite", FioRw::ReadWrite}}};
  const auto found = std::find_if(kModes.begin(), kModes.end(), [&](const auto& m) { return m.first == mode; });
  if (found == kModes.end()) {
    if (mode.find("trim") != std::string::npos) fail(o, fmt::format("{}: trims are not modelled by pcsim", label(o)));
    fail(o, fmt::format("{}: rw is one of read, write, randread, randwrite, rw (readwrite), randrw, with an optional ':N'", label(o)));
  }
  d.job.rw = found->second;
  const bool random = found < kModes.begin() + 3;
  d.job.rw_step = random ? 1 : 0;
  if (colon == std::string::npos) return;
  const std::string step = value.substr(colon + 1);
  if (random) {
    d.job.rw_step = io_count(o, step);
  } else {
    if (step.empty()) fail(o, fmt::format("{}: ':N' needs a size after ':'", label(o)));
    d.job.rw_step = parse_size(o, step, d.kb_base, true);
    if (d.job.rw_step < -kMaxBlock * 1024 || d.job.rw_step > kMaxBlock * 1024) fail(o, fmt::format("{}: the step is too large", label(o)));
  }
}

// Block sizes per direction, as bs and bsrange store them: an empty piece keeps that
// direction's size; the last piece given applies to the directions after it too.
template <typename Parse>
void set_block_sizes(Draft& d, const RawOption& o, std::vector<std::string> pieces, Parse parse) {
  if (pieces.size() == 4 && pieces.back().empty()) pieces.pop_back();
  if (pieces.size() > 3) fail(o, fmt::format("{}: at most three block sizes (read, write, trim)", label(o)));
  std::array<std::int64_t, 3> sizes{-1, -1, -1};
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (pieces[i].empty()) continue;
    sizes[i] = parse(pieces[i]);
    if (sizes[i] < 1 || sizes[i] > kMaxBlock) fail(o, fmt::format("{}: a block size is from 1 byte to 2 GiB", label(o)));
  }
  if (sizes[0] > 0) d.job.bs_read = sizes[0];
  if (pieces.size() == 1 && sizes[0] > 0) d.job.bs_write = d.bs_trim = sizes[0];
  if (pieces.size() == 2 && sizes[1] > 0) d.job.bs_write = d.bs_trim = sizes[1];
  if (pieces.size() == 3 && sizes[1] > 0) d.job.bs_write = sizes[1];
  if (pieces.size() == 3 && sizes[2] > 0) d.bs_trim = sizes[2];
}

void set_bs(Draft& d, const RawOption& o, Warnings&) {
  set_block_sizes(d, o, split_directions(required_text(o)), [&](const std::string& piece) { return parse_size(o, piece, d.kb_base); });
}

// bsrange splits on ',' only, each piece lo-hi or lo:hi. A range whose ends are equal is one
// block size (tiobench-example.fio's bsrange=4k-4k); a true range is not modelled.
void set_bsrange(Draft& d, const RawOption& o, Warnings&) {
  const std::string value = required_text(o);
  std::vector<std::string> pieces;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = value.find(',', begin);
    pieces.push_back(value.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  set_block_sizes(d, o, pieces, [&](const std::string& piece) {
    const std::size_t dash = piece.find_first_of("-:");
    const std::int64_t low = parse_size(o, piece.substr(0, dash), d.kb_base);
    const std::int64_t high = dash == std::string::npos ? low : parse_size(o, piece.substr(dash + 1), d.kb_base);
    if (low != high) fail(o, fmt::format("{}: a range of block sizes is not modelled by pcsim; give one size per direction", label(o)));
    return low;
  });
}

void set_file_service(Draft& d, const RawOption& o, Warnings&) {
  const std::string value = required_text(o);
  const std::size_t colon = value.find(':');
  const std::string type = value.substr(0, colon);
  if (type == "roundrobin") {
    d.job.file_service = FioFileService::RoundRobin;
  } else if (type == "sequential") {
    d.job.file_service = FioFileService::Sequential;
  } else if (type == "random") {
    d.job.file_service = FioFileService::Random;
  } else if (type == "zipf" || type == "pareto" || type == "normal" || type == "gauss") {
    fail(o, fmt::format("{}: a {} choice of files is not modelled by pcsim (roundrobin, sequential, random)", label(o), type));
  } else {
    fail(o, fmt::format("{}: file_service_type is roundrobin, sequential or random, with an optional ':N'", label(o)));
  }
  d.job.file_service_step = 1;
  if (colon == std::string::npos) return;
  d.job.file_service_step = io_count(o, value.substr(colon + 1));
}

void check_path(const RawOption& o, const std::string& name) {
  if (name.size() > 4095) fail(o, fmt::format("option '{}': a file name is at most 4095 bytes (PATH_MAX)", o.key));
}

// filename= adds to the files the job already has (its own or inherited), each prefixed with
// the first directory as it stands now (filesetup.c add_file).
void set_filename(Draft& d, const RawOption& o, Warnings&) {
  const std::vector<std::string> names = split_names(required_text(o));
  if (names.empty()) fail(o, fmt::format("{}: names no file", label(o)));
  const std::string prefix = d.directories.empty() ? std::string() : d.directories.front() + "/";
  for (const std::string& name : names) {
    if (name == "-") fail(o, fmt::format("{}: standard input or output is not modelled by pcsim", label(o)));
    check_path(o, prefix + name);
    if (static_cast<std::int64_t>(d.explicit_files.size()) >= d.limits->max_files) {
      fail(o, fmt::format("{}: more than the {} files a run may have{}", label(o), d.limits->max_files, d.limits->hint));
    }
    d.explicit_files.push_back(prefix + name);
  }
}

// Checked against the run's limit on files before any name is made.
void set_nrfiles(Draft& d, const RawOption& o, Warnings&) {
  d.nrfiles = parse_count(o, d.kb_base, 1, std::numeric_limits<std::int64_t>::max());
  if (d.nrfiles > d.limits->max_files) fail(o, fmt::format("{}: more than the {} files a run may have{}", label(o), d.limits->max_files, d.limits->hint));
}

void set_filename_format(Draft& d, const RawOption& o, Warnings&) {
  d.filename_format = required_text(o);
  std::string lowered = d.filename_format;
  std::transform(lowered.begin(), lowered.end(), lowered.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lowered.find("$clientuid") != std::string::npos) fail(o, fmt::format("{}: $clientuid (fio's client/server mode) is not modelled", label(o)));
  check_path(o, d.filename_format);
}

void set_directory(Draft& d, const RawOption& o, Warnings&) {
  d.directories = split_names(required_text(o));
  if (d.directories.empty()) fail(o, fmt::format("{}: names no folder", label(o)));
  for (const std::string& dir : d.directories) check_path(o, dir);
}

void set_ioengine(Draft& d, const RawOption& o, Warnings&) {
  const std::string engine = required_text(o);
  for (const char* sync : {"sync", "psync", "vsync", "pvsync", "pvsync2"}) {
    if (engine == sync) {
      d.job.ioengine = engine;
      return;
    }
  }
  fail(o, fmt::format("{} is not modelled: pcsim models one synchronous request at a time (sync, psync, vsync, pvsync, pvsync2)",
                      o.included ? "this ioengine" : "ioengine=" + engine));
}

void set_fadvise(Draft& d, const RawOption& o, Warnings&) {
  const std::string value = required_text(o);
  if (value == "0") d.job.fadvise = FioFadvise::None;
  else if (value == "1") d.job.fadvise = FioFadvise::Auto;
  else if (value == "sequential") d.job.fadvise = FioFadvise::Sequential;
  else if (value == "random") d.job.fadvise = FioFadvise::Random;
  else fail(o, fmt::format("{}: fadvise_hint is 0, 1, sequential or random", label(o)));
}

void set_kb_base(Draft& d, const RawOption& o, Warnings&) {
  if (o.value != "1024" && o.value != "1000") fail(o, fmt::format("{}: kb_base is 1024 or 1000", label(o)));
  d.kb_base = o.value == "1024" ? 1024 : 1000;
}

void set_rwmix(Draft& d, const RawOption& o, bool read) {
  const auto percent = static_cast<int>(parse_count(o, d.kb_base, 0, 100));
  d.job.rwmixread = read ? percent : 100 - percent;
}

// Values that make the option a no-op are accepted; any other is refused.
void accept_only(const RawOption& o, std::initializer_list<std::string_view> values, const char* why) {
  for (std::string_view v : values) {
    if (o.value == v) return;
  }
  fail(o, fmt::format("{} is not modelled by pcsim: {}", label(o), why));
}

const std::vector<Supported>& supported() {
  static const std::vector<Supported> kSupported{
      {"rw", "readwrite", set_rw},
      {"rwmixread", "", [](Draft& d, const RawOption& o, Warnings&) { set_rwmix(d, o, true); }},
      {"rwmixwrite", "", [](Draft& d, const RawOption& o, Warnings&) { set_rwmix(d, o, false); }},
      {"bs", "blocksize", set_bs},
      {"bsrange", "blocksize_range", set_bsrange},
      {"size", "", [](Draft& d, const RawOption& o, Warnings&) {
         const SizeOrPercent s = single_size_or_percent(d, o);
         d.job.size = s.bytes, d.job.size_percent = s.percent;
       }},
      {"filesize", "", [](Draft& d, const RawOption& o, Warnings&) {
         if (o.value.find_first_of(":-,") != std::string::npos) fail(o, fmt::format("{}: a range of file sizes is not modelled yet; give one size", label(o)));
         d.job.filesize = single_size(d, o);
       }},
      {"nrfiles", "nr_files", set_nrfiles},
      {"file_service_type", "", set_file_service},
      {"filename", "", set_filename},
      {"filename_format", "", set_filename_format},
      {"directory", "", set_directory},
      {"offset", "fileoffset", [](Draft& d, const RawOption& o, Warnings&) {
         const SizeOrPercent s = single_size_or_percent(d, o);
         d.job.offset = s.bytes, d.job.offset_percent = s.percent;
       }},
      {"offset_increment", "", [](Draft& d, const RawOption& o, Warnings&) {
         const SizeOrPercent s = single_size_or_percent(d, o);
         d.job.offset_increment = s.bytes, d.job.offset_increment_percent = s.percent;
       }},
      {"io_size", "io_limit", [](Draft& d, const RawOption& o, Warnings&) {
         const SizeOrPercent s = single_size_or_percent(d, o);
         d.job.io_size = s.bytes, d.job.io_size_percent = s.percent;
       }},
      {"number_ios", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.number_ios = parse_count(o, d.kb_base, 0, INT64_MAX); }},
      {"direct", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.direct = parse_bool(o); }},
      {"buffered", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.direct = !parse_bool(o); }},
      {"invalidate", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.invalidate = parse_bool(o); }},
      {"pre_read", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.pre_read = parse_bool(o); }},
      {"create_on_open", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.create_on_open = parse_bool(o); }},
      {"overwrite", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.overwrite = parse_bool(o); }},
      {"unlink", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.unlink = parse_bool(o); }},
      {"fsync", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.fsync = parse_count(o, d.kb_base, 0, kMaxUint32); }},
      {"fdatasync", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.fdatasync = parse_count(o, d.kb_base, 0, kMaxUint32); }},
      {"end_fsync", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.end_fsync = parse_bool(o); }},
      {"fsync_on_close", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.fsync_on_close = parse_bool(o); }},
      {"loops", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.loops = parse_count(o, d.kb_base, 1, 1'000'000'000); }},
      {"runtime", "timeout", [](Draft& d, const RawOption& o, Warnings&) { d.job.runtime = parse_time(o, 1.0); }},
      {"time_based", "", [](Draft& d, const RawOption& o, Warnings&) { d.time_based_asked = parse_flag(o); }},
      {"ramp_time", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.ramp_time = parse_time(o, 1.0); }},
      {"startdelay", "", [](Draft& d, const RawOption& o, Warnings&) {
         if (o.value.find_first_of(":-,") != std::string::npos) fail(o, fmt::format("{}: a random start delay (a range) is not modelled; give one time", label(o)));
         d.job.startdelay = parse_time(o, 1.0);
       }},
      {"thinktime", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.thinktime = parse_time(o, 1e-6); }},
      {"thinktime_blocks", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.thinktime_blocks = parse_count(o, d.kb_base, 1, kMaxUint32); }},
      {"randrepeat", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.randrepeat = parse_bool(o); }},
      {"randseed", "", [](Draft& d, const RawOption& o, Warnings&) {
         d.job.randseed = static_cast<std::uint64_t>(parse_count(o, d.kb_base, 0, INT64_MAX));
         d.job.randseed_given = true;
       }},
      {"norandommap", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.norandommap = parse_flag(o); }},
      {"fadvise_hint", "", set_fadvise},
      {"ioengine", "", set_ioengine},
      {"iodepth", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.iodepth = parse_count(o, d.kb_base, 1, 65536); }},
      {"numjobs", "", [](Draft& d, const RawOption& o, Warnings&) { d.numjobs = parse_count(o, d.kb_base, 1, d.limits->max_jobs); }},
      {"stonewall", "wait_for_previous", [](Draft& d, const RawOption& o, Warnings&) { d.stonewall = parse_flag(o); }},
      {"new_group", "", [](Draft& d, const RawOption& o, Warnings&) { d.new_group = parse_flag(o); }},
      {"wait_for", "", [](Draft& d, const RawOption& o, Warnings&) { d.wait_for = required_text(o); }},
      {"name", "", [](Draft& d, const RawOption& o, Warnings&) { d.job.name = required_text(o); }},
      {"kb_base", "", set_kb_base},
      {"sync", "", [](Draft&, const RawOption& o, Warnings&) { accept_only(o, {"none", "0"}, "O_SYNC and O_DSYNC writes"); }},
      {"random_distribution", "", [](Draft&, const RawOption& o, Warnings&) {
         accept_only(o, {"random"}, "pcsim draws offsets uniformly (random_distribution=random)");
       }},
  };
  return kSupported;
}

// Options fio knows whose refusal deserves a reason beyond "not modelled".
const char* refusal_reason(const std::string& key) {
  if (key == "lockmem") return ": it pins memory the page cache could otherwise use";
  if (key == "exitall" || key == "exit_what" || key == "exitall_on_error") return ": it ends other jobs early";
  if (key.rfind("verify", 0) == 0 || key == "do_verify") return ": it reads back and checks written data";
  if (key.rfind("rate", 0) == 0) return ": rate limits are not modelled";
  return "";
}

// Unknown names: fio's own message would be "Bad option"; pcsim names the closest it knows.
[[noreturn]] void refuse_unknown(const RawOption& o) {
  if (!option_shaped(o.key)) fail(o, "not an option line of a fio job file (an option's name is letters, digits and '_')");
  if (fio_option_names().count(o.key) != 0) {
    fail(o, fmt::format("option '{}' is not modelled by pcsim{}", o.key, refusal_reason(o.key)));
  }
  const std::string guess = closest(o.key, fio_option_names());
  fail(o, fmt::format("unknown option '{}' (fio does not know it either){}", o.key,
                      guess.empty() ? std::string() : fmt::format("; did you mean '{}'?", guess)));
}

void ignore(const IgnoredOption& ignored, const RawOption& o, Warnings& warnings) {
  if (ignored.value == IgnoredOption::Value::Bool) parse_bool(o);
  if (ignored.value == IgnoredOption::Value::Flag) parse_flag(o);
  warnings.add(o.key, fmt::format("{}option '{}' is ignored: {}", where(o.file, o.line), o.key, ignored.why));
}

void apply(Draft& draft, const RawOption& o, Warnings& warnings) {
  for (const Supported& s : supported()) {
    if (o.key == s.name || (!s.alias.empty() && o.key == s.alias)) return s.set(draft, o, warnings);
  }
  for (const IgnoredOption& ignored : ignored_options()) {
    if (o.key == ignored.name) return ignore(ignored, o, warnings);
  }
  refuse_unknown(o);
}

// parse.c opt_cmp: kb_base (and unit_base, lockfile, cpus_allowed_policy) first, filename and
// filename_format last.
int priority(const std::string& key) {
  if (key == "kb_base" || key == "unit_base" || key == "lockfile" || key == "cpus_allowed_policy") return 0;
  if (key == "filename" || key == "filename_format") return 2;
  return 1;
}

}  // namespace

void Warnings::add(const std::string& key, const std::string& text) {
  if (seen.insert(key).second) list.push_back(text);
}

void apply_options(Draft& draft, const std::vector<RawOption>& options, Warnings& warnings) {
  std::vector<const RawOption*> order;
  order.reserve(options.size());
  for (const RawOption& o : options) order.push_back(&o);
  std::stable_sort(order.begin(), order.end(), [](const RawOption* a, const RawOption* b) { return priority(a->key) < priority(b->key); });
  for (const RawOption* o : order) apply(draft, *o, warnings);
}

std::vector<std::string> supported_option_names() {
  std::vector<std::string> names;
  for (const Supported& s : supported()) {
    names.emplace_back(s.name);
    if (!s.alias.empty()) names.emplace_back(s.alias);
  }
  return names;
}

}  // namespace pagecache::formats::fio
