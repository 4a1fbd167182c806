// A resolved scenario written back as TOML, every default and every expanded shorthand
// spelled out (`pcsim show`). Reading it back gives the same scenario.

#include <pagecache/cache_policies.hpp>
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>
#include <pagecache/units.hpp>

#include "text/printable.hpp"
#include "text/utf8.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <sstream>
#include <string>

namespace pagecache {

namespace {

// Strings and lists are written by toml++, as basic strings ("..." with escapes, as before):
// its literal and multi-line forms drop a leading line break and end early at ''' (toml++ 3.3).
std::string toml_text(const toml::node& value) {
  std::ostringstream out;
  out << toml::toml_formatter(value, toml::format_flags::allow_unicode_strings | toml::format_flags::indent_array_elements);
  return out.str();
}

// TOML strings are Unicode: a name that is not valid UTF-8 (only an embedding program can make
// one) is shown with U+FFFD in place of each ill-formed part, as in the JSON outputs.
std::string quoted(const std::string& s) { return toml_text(toml::value<std::string>(text::valid_utf8(s))); }

std::string list(const std::vector<std::string>& items) {
  toml::array array;
  for (const std::string& item : items) array.push_back(text::valid_utf8(item));
  return toml_text(array);
}

// An access of parts of one file: its pattern's keys only.
void write_file_access(std::string& out, const std::string& table, const AccessSpec& a) {
  out += fmt::format("\n[[{}.access]]\nfile = {}\npattern = {}\nmode = {}\n", table, quoted(a.file), quoted(to_string(a.pattern)),
                     quoted(to_string(a.mode)));
  if (a.mode == AccessMode::Read) out += fmt::format("advice = {}\n", quoted(to_string(a.advice)));
  out += fmt::format("request = {}\n", quoted(units::format_size(a.request)));
  if (a.pattern == AccessPattern::Ranges) {
    std::string ranges;
    for (const auto& [offset, length] : a.ranges) {
      ranges += fmt::format("{}[{}, {}]", ranges.empty() ? "" : ", ", quoted(units::format_size(offset)), quoted(units::format_size(length)));
    }
    out += fmt::format("ranges = [{}]\n", ranges);
  } else {
    out += fmt::format("offset = {}\nlength = {}\n", quoted(units::format_size(a.offset)), quoted(units::format_size(a.length)));
    if (a.pattern == AccessPattern::Strided) out += fmt::format("stride = {}\n", quoted(units::format_size(a.stride)));
    if (a.pattern == AccessPattern::Random) out += fmt::format("seed = {}\nreplacement = {}\nreshuffle = {}\n", a.seed, a.replacement, a.reshuffle);
    out += fmt::format("count = {}\n", a.count);
  }
  if (a.runtime > 0.0) out += fmt::format("runtime = {}\n", quoted(units::format_duration(a.runtime)));
  out += fmt::format("invalidate = {}\nrepeat = {}\n", a.invalidate, a.repeat);
  if (a.drop_after) out += "drop_after = true\n";
}

void write_task(std::string& out, const std::string& table, const TaskSpec& t, bool in_workflow) {
  out += fmt::format("\n[[{}]]\nname = {}\n", table, quoted(t.name));
  if (in_workflow && !t.host.empty()) out += fmt::format("host = {}\n", quoted(t.host));
  if (in_workflow) out += fmt::format("cores = {}\n", t.cores);
  out += fmt::format("memory = {}\nread = {}\ncompute = {}\nwrite = {}\nchunk_size = {}\n", quoted(units::format_size(t.memory)),
                     list(t.reads), quoted(units::format_duration(t.compute)), list(t.writes), quoted(units::format_size(t.chunk_size)));
  out += fmt::format("fsync = {}\ndirect_io = {}\ndelete = {}\n", t.fsync, t.direct_io, list(t.deletes));
  if (in_workflow) out += fmt::format("after = {}\n", list(t.after));
  if (t.memory_limits.max > 0) out += fmt::format("memory_max = {}\n", quoted(units::format_size(t.memory_limits.max)));
  if (t.memory_limits.high > 0) out += fmt::format("memory_high = {}\n", quoted(units::format_size(t.memory_limits.high)));
  for (const AccessSpec& a : t.accesses) {
    if (!a.file.empty()) {
      write_file_access(out, table, a);
      continue;
    }
    out += fmt::format("\n[[{}.access]]\nfiles = {}\npattern = {}\n", table, quoted(a.file_set), quoted(to_string(a.pattern)));
    if (a.pattern == AccessPattern::Random) out += fmt::format("seed = {}\nreplacement = {}\n", a.seed, a.replacement);
    out += fmt::format("count = {}\nrepeat = {}\n", a.count, a.repeat);
  }
}

// A platform file shown alone may not give what a run needs (load_platform): the key is left
// for the user to fill in.
std::string size_or_ask(const char* key, std::int64_t v) {
  return v > 0 ? fmt::format("{} = {}\n", key, quoted(units::format_size(v))) : fmt::format("# {} = ?  (not in the platform file)\n", key);
}
std::string rate_or_ask(const char* key, double v) {
  return v > 0.0 ? fmt::format("{} = {}\n", key, quoted(units::format_bandwidth(v))) : fmt::format("# {} = ?  (not in the platform file)\n", key);
}

void write_memory(std::string& out, const HostConfig& h) {
  out += size_or_ask("memory", h.memory);
  out += fmt::format("memory_in_use = {}\n", quoted(units::format_size(h.memory_in_use)));
  out += rate_or_ask("memory_read_bw", h.memory_bandwidth.read) + rate_or_ask("memory_write_bw", h.memory_bandwidth.write) +
         rate_or_ask("memory_aggregate_read_bw", h.memory_bandwidth.aggregate_read) +
         rate_or_ask("memory_aggregate_write_bw", h.memory_bandwidth.aggregate_write);
  out += fmt::format("memory_first_touch_bw = {}\n", quoted(units::format_bandwidth(h.memory_bandwidth.first_touch)));
  if (h.memory_bandwidth.reclaimed_write > 0.0) {
    out += fmt::format("memory_reclaimed_write_bw = {}\n", quoted(units::format_bandwidth(h.memory_bandwidth.reclaimed_write)));
  }
  if (h.request_time > 0.0) out += fmt::format("request_time = {}\n", quoted(units::format_duration(h.request_time)));
  if (h.memory_bandwidth.cold_fault > 0.0) {
    out += fmt::format("memory_cold_fault_bw = {}\npage_reporting_delay = {}\nmemory_freed_at_start = {}\n",
                       quoted(units::format_bandwidth(h.memory_bandwidth.cold_fault)), quoted(units::format_duration(h.page_reporting_delay)),
                       quoted(units::format_size(h.memory_freed_at_start)));
    if (h.memory_bandwidth.aggregate_cold_fault > 0.0) {
      out += fmt::format("memory_aggregate_cold_fault_bw = {}\n", quoted(units::format_bandwidth(h.memory_bandwidth.aggregate_cold_fault)));
    }
  }
}

void write_page_cache(std::string& out, const CacheSettings& cache) {
  out += fmt::format(
      "\n[hosts.page_cache]\nmode = {}\ndirty_ratio = {}\ndirty_background_ratio = {}\ndirty_expire = {}\nwriteback_interval = {}\n",
      quoted(cache.write_mode == WriteMode::Writeback ? "writeback" : "writethrough"), cache.dirty_ratio, cache.dirty_background_ratio,
      quoted(units::format_duration(cache.dirty_expire)), quoted(units::format_duration(cache.writeback_interval)));
  out += fmt::format("policy = {}\n", quoted(cache.policy));
  // The policy's own parameters, as its declaration lists them (a preset has none), then the
  // host model's switches.
  if (const PolicyDeclaration* policy = find_cache_policy(cache.policy)) {
    for (const PolicyParameter& p : policy->parameters) out += fmt::format("{} = {}\n", p.key, format_parameter(p.kind, cache.value(p.key)));
  }
  for (const PolicyParameter& p : host_model_switches()) out += fmt::format("{} = {}\n", p.key, cache.get(p.key));
}

void write_disk(std::string& out, const DiskSpec& d) {
  out += fmt::format("\n[[hosts.disks]]\nname = {}\nread_bw = {}\nwrite_bw = {}\n", quoted(d.name), quoted(units::format_bandwidth(d.read_bw)),
                     quoted(units::format_bandwidth(d.write_bw)));
  if (d.aggregate_read_bw > 0.0) out += fmt::format("aggregate_read_bw = {}\n", quoted(units::format_bandwidth(d.aggregate_read_bw)));
  if (d.aggregate_write_bw > 0.0) out += fmt::format("aggregate_write_bw = {}\n", quoted(units::format_bandwidth(d.aggregate_write_bw)));
  out += fmt::format("capacity = {}\n", quoted(units::format_size(d.capacity)));
  // Only when set, as the scenarios that predate them never give them.
  if (d.request_latency > 0.0) out += fmt::format("request_latency = {}\n", quoted(units::format_duration(d.request_latency)));
  if (d.read_ahead > 0) out += fmt::format("read_ahead = {}\n", quoted(units::format_size(d.read_ahead)));
  if (d.max_request > 0) out += fmt::format("max_request = {}\n", quoted(units::format_size(d.max_request)));
  if (d.write_cache > 0) {
    out += fmt::format("write_cache = {}\nsustained_write_bw = {}\n", quoted(units::format_size(d.write_cache)),
                       quoted(units::format_bandwidth(d.sustained_write_bw)));
  }
}

void write_host(std::string& out, const HostConfig& h) {
  out += fmt::format("\n[[hosts]]\nname = {}\ncores = {}\n", quoted(h.name), h.cores);
  if (h.speed > 0.0) out += fmt::format("speed = {}\n", h.speed);  // flop/s, read back to the same double
  write_memory(out, h);
  write_page_cache(out, h.cache);
  if (h.numa.nodes > 1) {
    out += fmt::format("\n[hosts.numa]\nnodes = {}\nremote_copy_ratio = {}\nremote_first_touch_ratio = {}\nremote_aggregate_ratio = {}\n", h.numa.nodes,
                       h.numa.remote.copy, h.numa.remote.first_touch, h.numa.remote.aggregate);
  }
  for (const DiskSpec& d : h.disks) write_disk(out, d);
}

void write_network(std::string& out, const Scenario& s) {
  for (const LinkSpec& l : s.links) {
    out += fmt::format("\n[[links]]\nname = {}\nbandwidth = {}\nlatency = {}\nsharing = {}\n", quoted(l.name),
                       quoted(units::format_bandwidth(l.bandwidth)), quoted(units::format_duration(l.latency)),
                       quoted(l.sharing == LinkSharing::Fatpipe ? "fatpipe" : "shared"));
    if (!l.host_a.empty()) out += fmt::format("hosts = {}\n", list({l.host_a, l.host_b}));
  }
  for (const RouteSpec& r : s.routes) {
    out += fmt::format("\n[[routes]]\nhosts = {}\nlinks = {}\n", list({r.host_a, r.host_b}), list(r.links));
  }
}

void write_work(std::string& out, const Scenario& s) {
  for (const AppSpec& a : s.apps) {
    out += fmt::format("\n[[apps]]\nname = {}\nhost = {}\n", quoted(a.name), quoted(a.host));
    if (a.memory_max > 0) out += fmt::format("memory_max = {}\n", quoted(units::format_size(a.memory_max)));
    if (a.memory_high > 0) out += fmt::format("memory_high = {}\n", quoted(units::format_size(a.memory_high)));
    if (!a.after.empty()) out += fmt::format("after = {}\n", list(a.after));
    for (const TaskSpec& t : a.tasks) write_task(out, "apps.tasks", t, false);
  }
  for (const WorkflowSpec& w : s.workflows) {
    out += fmt::format("\n[workflow]\nname = {}\n", quoted(w.name));
    if (w.hosts.size() == 1) out += fmt::format("host = {}\n", quoted(w.hosts.front()));
    else out += fmt::format("hosts = {}\n", list(w.hosts));
    for (const TaskSpec& t : w.tasks) write_task(out, "workflow.tasks", t, true);
  }
}

}  // namespace

std::string to_toml(const Scenario& s) {
  // A comment ends at a line break and may hold no control character: the path is printable().
  std::string out = fmt::format("# resolved from {}\n", text::printable(s.source));
  if (!s.title.empty()) out += fmt::format("title = {}\n", quoted(s.title));
  out += fmt::format("profile = {}\nmemory_sample_interval = {}\ntrace = {}\n", quoted(to_string(s.profile)),
                     quoted(units::format_duration(s.memory_sample_interval)), s.trace);
  for (const HostConfig& h : s.hosts) write_host(out, h);
  write_network(out, s);
  for (const FileSpec& f : s.files) {
    out += fmt::format("\n[[files]]\nname = {}\nsize = {}\nhost = {}\ndisk = {}\ncached = {}\n", quoted(f.name),
                       quoted(units::format_size(f.size)), quoted(f.host), quoted(f.disk), f.cached);
  }
  // A set is one table, whatever its count: 10^6 files are not listed.
  for (const FileSetSpec& f : s.file_sets) {
    out += fmt::format("\n[[file_sets]]\nname = {}\ncount = {}\nsize = {}\nhost = {}\ndisk = {}\ncached = {}\n", quoted(f.name), f.count,
                       quoted(units::format_size(f.size)), quoted(f.host), quoted(f.disk), f.cached);
  }
  write_work(out, s);
  return out;
}

}  // namespace pagecache
