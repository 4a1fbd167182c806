#include "report/trace_json.hpp"

#include "text/json_string.hpp"

#include <pagecache/version.hpp>

#include <fmt/compile.h>

namespace pagecache::report {

namespace {

// Seconds of simulated time as microseconds, to the nanosecond.
struct Micros {
  double seconds;
};

}  // namespace

}  // namespace pagecache::report

template <>
struct fmt::formatter<pagecache::report::Micros> : fmt::formatter<double> {
  auto format(pagecache::report::Micros t, format_context& ctx) const { return fmt::format_to(ctx.out(), "{:.3f}", t.seconds * 1e6); }
};

namespace pagecache::report {

using text::json_string;

void TraceJson::on_start(const TraceStart& start) {
  hosts_.assign(start.hosts.begin(), start.hosts.end());
  auto meta = [this](std::uint32_t pid, const std::string& name, int sort) {
    fmt::format_to(std::back_inserter(metadata_), "{{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":{},\"tid\":0,\"ts\":0,\"args\":{{\"name\":{}}}}},\n",
                   pid, json_string(name));
    fmt::format_to(std::back_inserter(metadata_),
                   "{{\"ph\":\"M\",\"name\":\"process_sort_index\",\"pid\":{},\"tid\":0,\"ts\":0,\"args\":{{\"sort_index\":{}}}}},\n", pid, sort);
  };
  meta(1, "applications", 0);
  for (std::uint32_t h = 0; h < hosts_.size(); ++h) meta(host_pid(h), "host " + hosts_[h], static_cast<int>(h) + 1);
  meta(host_pid(static_cast<std::uint32_t>(hosts_.size())), "devices", static_cast<int>(hosts_.size()) + 1);
}

TraceJson::Lane& TraceJson::lane_for(std::string_view app, std::string_view task, double start) {
  auto it = apps_.find(app);
  if (it == apps_.end()) it = apps_.emplace(std::string(app), AppTrack{}).first;
  AppTrack& track = it->second;
  auto free_lane = [&](std::size_t i) { return track.lanes[i].last_end <= start; };
  std::size_t lane = track.lanes.size();
  if (const auto own = track.task_lane.find(task); own != track.task_lane.end() && free_lane(own->second)) {
    lane = own->second;
  } else {
    for (std::size_t i = 0; i < track.lanes.size(); ++i) {
      if (free_lane(i)) {
        lane = i;
        break;
      }
    }
  }
  if (lane == track.lanes.size()) {
    const std::uint32_t tid = next_tid_++;
    track.lanes.push_back({tid, start});
    const std::string name = lane == 0 ? std::string(app) : fmt::format("{} #{}", app, lane + 1);
    fmt::format_to(std::back_inserter(metadata_), "{{\"ph\":\"M\",\"name\":\"thread_name\",\"pid\":1,\"tid\":{},\"ts\":0,\"args\":{{\"name\":{}}}}},\n",
                   tid, json_string(name));
  }
  track.task_lane.insert_or_assign(std::string(task), lane);
  return track.lanes[lane];
}

void TraceJson::on_phase(const PhaseEvent& e) {
  Lane& lane = lane_for(e.app, e.task, e.start);
  lane.last_end = e.end;
  const std::uint32_t tid = lane.tid;
  // Named by task and phase: Perfetto shows a slice's name on it, so the task shows without a click.
  const std::string name = fmt::format("{} {}", e.task, to_string(e.kind));
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"X\",\"cat\":\"phase\",\"name\":{},\"pid\":1,\"tid\":{},\"ts\":{},\"dur\":{:.3f},"
                 "\"args\":{{\"task\":{},\"host\":{},\"bytes\":{},\"cache_bytes\":{},\"disk_bytes\":{}}}}},\n",
                 json_string(name), tid, Micros{e.start}, (e.end - e.start) * 1e6, json_string(e.task), json_string(hosts_.at(e.host)), e.bytes,
                 e.cache_bytes, e.disk_bytes);
}

bool TraceJson::room_for_detail() {
  if (events_.size() < max_bytes_) return true;
  truncated_ = true;
  return false;
}

void TraceJson::on_flow(const FlowEvent& e) {
  if (!room_for_detail() || e.resources.empty()) return;
  std::string route;
  for (const std::string_view r : e.resources) route += (route.empty() ? "" : " > ") + std::string(r);
  const std::uint64_t id = next_id_++;
  const std::uint32_t pid = host_pid(static_cast<std::uint32_t>(hosts_.size()));
  const std::string name = json_string(e.resources.front());
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"b\",\"cat\":\"flow\",\"name\":{},\"id\":{},\"pid\":{},\"tid\":0,\"ts\":{},\"args\":{{\"work\":{:.0f},\"route\":{}}}}},\n"
                 "{{\"ph\":\"e\",\"cat\":\"flow\",\"name\":{},\"id\":{},\"pid\":{},\"tid\":0,\"ts\":{}}},\n",
                 name, id, pid, Micros{e.start}, e.work, json_string(route), name, id, pid, Micros{e.end});
}

void TraceJson::on_flush(const FlushEvent& e) {
  if (!room_for_detail()) return;
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"i\",\"s\":\"p\",\"cat\":\"flush\",\"name\":\"flush ({})\",\"pid\":{},\"tid\":0,\"ts\":{},\"args\":{{\"bytes\":{}}}}},\n",
                 to_string(e.cause), host_pid(e.host), Micros{e.time}, e.bytes);
}

void TraceJson::on_eviction(const EvictionEvent& e) {
  if (!room_for_detail()) return;
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"i\",\"s\":\"p\",\"cat\":\"eviction\",\"name\":\"eviction\",\"pid\":{},\"tid\":0,\"ts\":{},\"args\":{{\"bytes\":{}}}}},\n",
                 host_pid(e.host), Micros{e.time}, e.bytes);
}

void TraceJson::on_throttle(const ThrottleEvent& e) {
  if (!room_for_detail()) return;
  const std::uint64_t id = next_id_++;
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"b\",\"cat\":\"throttle\",\"name\":\"throttled\",\"id\":{},\"pid\":{},\"tid\":0,\"ts\":{}}},\n"
                 "{{\"ph\":\"e\",\"cat\":\"throttle\",\"name\":\"throttled\",\"id\":{},\"pid\":{},\"tid\":0,\"ts\":{}}},\n",
                 id, host_pid(e.host), Micros{e.start}, id, host_pid(e.host), Micros{e.end});
}

void TraceJson::on_memory(const MemoryEvent& e) {
  const MemoryState& m = e.state;
  // Pages being filled by copies in flight are counted as cached, as memory.csv does.
  const std::int64_t clean = m.cached + m.reserved - m.dirty - m.writeback;
  fmt::format_to(std::back_inserter(events_),
                 "{{\"ph\":\"C\",\"name\":\"memory (bytes)\",\"pid\":{},\"tid\":0,\"ts\":{},"
                 "\"args\":{{\"free\":{},\"anonymous\":{},\"cached clean\":{},\"dirty\":{},\"writeback\":{}}}}},\n",
                 host_pid(e.host), Micros{e.time}, m.free, m.anonymous, clean, m.dirty, m.writeback);
}

std::string TraceJson::text(const std::string& scenario) const {
  std::string out = fmt::format("{{\"displayTimeUnit\":\"ms\",\"otherData\":{{\"generator\":\"pcsim {}\",\"scenario\":{},\"time\":\"simulated\",\"truncated\":{}}},\n\"traceEvents\":[\n",
                                kVersion, json_string(scenario), truncated_ ? "true" : "false");
  out.append(metadata_.data(), metadata_.size());
  out.append(events_.data(), events_.size());
  // The last event's ",\n" ends the list as "\n]}" (an empty run still has its metadata).
  if (out.size() >= 2 && out.compare(out.size() - 2, 2, ",\n") == 0) out.resize(out.size() - 2);
  out += "\n]}\n";
  return out;
}

}  // namespace pagecache::report
