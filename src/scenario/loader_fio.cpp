// A scenario's [fio] table: the jobs of a fio job file (formats/fio/job_file.hpp) as applications of
// the scenario's host. Each job (each numjobs clone) is an application of one task whose access
// is the job's I/O, in the order fio starts them (stonewall, wait_for: AppSpec::after); each
// file a job names is a file of the host's disk, as large as the jobs' regions need, on the disk
// and not cached at the start. Before the jobs, an application of its own lays out the files
// jobs read or overwrite, as fio does. What fio does that pcsim does not model yet is refused,
// naming the job's section and the option.

#include "formats/fio/job_file.hpp"
#include "scenario/limits.hpp"
#include "scenario/loader_sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace pagecache::scenario {

using namespace formats::fio;  // the fio reader's jobs

namespace {

// "JOB.fio:12: job 'name'": where a job's refusals point.
std::string place_of(const FioJobFile& f, const FioJob& job) { return fmt::format("{}:{}: job '{}'", f.path, job.line, job.section); }

[[noreturn]] void refuse(const FioJobFile& f, const FioJob& job, const std::string& option, const std::string& why) {
  throw ConfigError(fmt::format("{}: {}: {}", place_of(f, job), option, why), InputPlace{.file = f.path, .line = job.line, .key = option});
}

bool is_random(FioRw rw) { return rw == FioRw::RandRead || rw == FioRw::RandWrite || rw == FioRw::RandReadWrite; }
bool writes(FioRw rw) { return rw == FioRw::Write || rw == FioRw::RandWrite; }

// What pcsim cannot run yet, named.
void refuse_unmodelled(const FioJobFile& f, const FioJob& job) {
  const auto no = [&](bool condition, const char* option, const char* why) {
    if (condition) refuse(f, job, option, why);
  };
  no(job.rw == FioRw::ReadWrite || job.rw == FioRw::RandReadWrite, "rw", "mixed reads and writes are not modelled yet");
  no(job.rw_step != 0 && !(is_random(job.rw) && job.rw_step == 1), "rw", "an offset step (rw=...:N) is not modelled yet");
  no(job.files.size() > 1 && job.file_service != FioFileService::Sequential, "nrfiles",
     "several files served in turn are not modelled yet (file_service_type=sequential is)");
  no(job.fsync > 0 || job.fdatasync > 0, job.fsync > 0 ? "fsync" : "fdatasync", "a sync every N writes is not modelled yet");
  no(job.time_based, "time_based", "runs bounded by time are not modelled yet");
  no(job.thinktime > 0.0, "thinktime", "think time between requests is not modelled yet");
  no(job.startdelay > 0.0, "startdelay", "a start delay is not modelled yet");
  no(job.ramp_time > 0.0, "ramp_time", "a ramp time is not modelled yet");
  no(job.pre_read, "pre_read", "reading the files before the job is not modelled yet");
  no(job.create_on_open, "create_on_open", "files made by the job's open are not modelled yet");
  no(job.files.size() > 1 && (job.io_size > 0 || job.number_ios > 0 || job.runtime > 0.0),
     job.io_size > 0 ? "io_size" : job.number_ios > 0 ? "number_ios" : "runtime", "a bound on the I/O of a job of several files is not modelled yet");
  no(job.size_percent > 0 || job.offset_percent > 0 || job.offset_increment_percent > 0 || job.io_size_percent > 0, "size",
     "sizes in percent of existing files are not modelled (pcsim's files exist only in the simulation)");
}

// The bytes of each of the job's files that it does I/O on: [start, start + length).
struct Region {
  std::int64_t start = 0;
  std::int64_t length = 0;
};

Region region_of(const FioJobFile& f, const FioJob& job) {
  const std::int64_t start = job.offset + job.jobnum * job.offset_increment;
  const auto files = static_cast<std::int64_t>(job.files.size());
  if (job.filesize > 0) {
    // With filesize the region is the file from the offset on (fio's setup_files).
    if (start >= job.filesize) refuse(f, job, "offset", fmt::format("{} is not within filesize={}", start, job.filesize));
    return {start, job.filesize - start};
  }
  if (job.size <= 0) refuse(f, job, "size", "needed: pcsim's files exist only in the simulation, so their size must be given (size= or filesize=)");
  const std::int64_t bs = std::max(job.bs_read, job.bs_write);
  const std::int64_t each = job.size / files;
  if (each < bs) refuse(f, job, "size", fmt::format("{} bytes per file, less than a block ({} bytes)", each, bs));
  return {start, each};
}

// The job's access of one of its files.
AccessSpec access_of(const FioJob& job, std::size_t index, const std::string& file, Region region) {
  AccessSpec a;
  a.file = file;
  a.pattern = is_random(job.rw) ? AccessPattern::Random : AccessPattern::Sequential;
  a.mode = writes(job.rw) ? AccessMode::Write : AccessMode::Read;
  a.request = writes(job.rw) ? job.bs_write : job.bs_read;
  a.offset = region.start;
  a.length = region.length;
  // Each block of the region once (or io_size's worth, past the region's end again from its
  // start, as fio wraps), at most number_ios requests.
  std::int64_t count = (region.length + a.request - 1) / a.request;
  if (job.io_size > 0) count = (job.io_size + a.request - 1) / a.request;
  if (job.number_ios > 0) count = std::min(count, job.number_ios);
  a.count = count;
  a.replacement = a.pattern == AccessPattern::Random && job.norandommap;
  // Each job its own stream, the same run after run (fio mixes randseed with the job's number).
  a.seed = job.randseed + index;
  a.reshuffle = a.pattern != AccessPattern::Random || !job.randrepeat;
  a.invalidate = job.invalidate;
  a.runtime = job.runtime;
  a.repeat = job.loops;
  if (a.mode == AccessMode::Read) {
    switch (job.fadvise) {
      case FioFadvise::None: a.advice = AccessAdvice::Normal; break;
      case FioFadvise::Auto: a.advice = is_random(job.rw) ? AccessAdvice::Random : AccessAdvice::Sequential; break;
      case FioFadvise::Sequential: a.advice = AccessAdvice::Sequential; break;
      case FioFadvise::Random: a.advice = AccessAdvice::Random; break;
    }
  }
  return a;
}

// Application names, one per job: the reported name, with ".N" for a clone and "#I" if two
// sections share a name (fio reports clones under their job's name; an application's must be
// its own, for `after`).
std::vector<std::string> app_names(const FioJobFile& f) {
  std::map<std::string, int> sections;
  for (const FioJob& job : f.jobs) {
    if (job.jobnum == 0) ++sections[job.name];
  }
  std::vector<std::string> names;
  names.reserve(f.jobs.size());
  for (std::size_t i = 0; i < f.jobs.size(); ++i) {
    const FioJob& job = f.jobs[i];
    std::string name = job.jobnum == 0 ? job.name : fmt::format("{}.{}", job.name, job.jobnum);
    if (sections[job.name] > 1) name += fmt::format("#{}", i);
    names.push_back(std::move(name));
  }
  return names;
}

}  // namespace

namespace {

// Where a fio run goes: [fio]'s host, disk and memory cgroup.
struct FioPlace {
  std::string host;
  std::string disk;
  MemoryLimits limits;
};

FioPlace place_of_run(TomlReader& fr, const Scenario& s) {
  FioPlace p;
  p.host = fr.name("host", s.hosts.front().name);
  const auto on = std::find_if(s.hosts.begin(), s.hosts.end(), [&](const HostConfig& h) { return h.name == p.host; });
  if (on == s.hosts.end()) fr.fail("host", fmt::format("no host named '{}'", p.host));
  if (on->disks.empty()) fr.fail("host", fmt::format("host '{}' has no disk for the jobs' files", p.host));
  p.disk = fr.name("disk", on->disks.front().name);
  if (std::none_of(on->disks.begin(), on->disks.end(), [&](const DiskSpec& d) { return d.name == p.disk; })) {
    fr.fail("disk", fmt::format("host '{}' has no disk named '{}'", p.host, p.disk));
  }
  // fio run in a memory cgroup (systemd-run -p MemoryMax=..., or validate --here --fio).
  p.limits = read_memory_limits(fr, "the fio run's");
  return p;
}

// Each job's region, and each file's size: as large as its jobs' regions need.
struct FileUse {
  std::vector<Region> regions;
  std::map<std::string, std::int64_t> extent;
};

// The jobs' files, each as large as the regions its jobs use.
FileUse add_files(TomlReader& fr, const FioJobFile& jobs, const FioPlace& place, Scenario& s, Origins& origins) {
  FileUse use;
  std::map<std::string, std::int64_t>& extent = use.extent;
  std::vector<std::string> order;
  std::vector<Region>& regions = use.regions;
  for (const FioJob& job : jobs.jobs) {
    refuse_unmodelled(jobs, job);
    regions.push_back(region_of(jobs, job));
    for (const std::string& name : job.files) {
      auto [it, added] = extent.emplace(name, 0);
      if (added) order.push_back(name);
      it->second = std::max(it->second, regions.back().start + regions.back().length);
    }
  }
  std::set<std::string> taken;
  for (const FileSpec& f : s.files) taken.insert(f.name);
  for (const std::string& name : order) {
    if (taken.count(name) != 0) fr.fail("file", fmt::format("{} names file '{}', which the scenario has already", jobs.path, name));
    s.files.push_back(FileSpec{.name = name, .size = extent[name], .host = place.host, .disk = place.disk, .cached = false});
    origins.files.push_back(Origin::elsewhere(fmt::format("{}: file '{}'", jobs.path, name)));
  }
  return use;
}

// fio sets up each job's files before any job starts, job after job (create_serialize): a
// file smaller than the job's region needs is extended. A job that only writes allocates it
// (fallocate, no data); one that reads or overwrites lays it out: writes it from byte 0 in its
// write requests, fsyncs it (create_fsync) and drops it from the page cache (filesetup.c,
// extend_file). A task per file laid out; on a virtual machine they leave memory freed just
// before the jobs start (docs/model.md §6.16).
struct Layout {
  const FioJob* job;
  const std::string* file;
  std::int64_t length;  // the file's size once laid out
};

std::vector<Layout> layouts_of(const FioJobFile& jobs, const FileUse& use) {
  std::vector<Layout> layouts;
  std::map<std::string_view, std::int64_t> size;  // each file's size as set up so far
  for (std::size_t j = 0; j < jobs.jobs.size(); ++j) {
    const FioJob& job = jobs.jobs[j];
    const std::int64_t needed = use.regions[j].start + use.regions[j].length;
    for (const std::string& name : job.files) {
      std::int64_t& has = size[name];
      if (has >= needed) continue;  // large enough: left as it is
      has = needed;
      if (writes(job.rw) && !job.overwrite) continue;
      layouts.push_back(Layout{&job, &name, needed});
    }
  }
  return layouts;
}

std::vector<TaskSpec> layout_tasks(const std::vector<Layout>& layouts) {
  std::vector<TaskSpec> tasks;
  tasks.reserve(layouts.size());
  for (const Layout& layout : layouts) {
    TaskSpec& task = tasks.emplace_back();
    task.name = "layout";
    task.chunk_size = 100'000'000;
    task.fsync = true;
    AccessSpec& a = task.accesses.emplace_back();
    a.file = *layout.file;
    a.mode = AccessMode::Write;
    a.request = layout.job->bs_write;
    a.length = layout.length;
    a.count = (a.length + a.request - 1) / a.request;
    a.drop_after = true;
  }
  return tasks;
}

// The run's limit on tasks (a task per job, one per file laid out), before any is made.
void check_task_count(const FioJobFile& jobs, const std::vector<Layout>& layouts, const ScenarioLimits& limits) {
  const double tasks = static_cast<double>(jobs.jobs.size()) + static_cast<double>(layouts.size());
  if (tasks <= static_cast<double>(limits.max_tasks)) return;
  const FioJob& job = layouts.empty() ? jobs.jobs.back() : *layouts.back().job;
  refuse(jobs, job, layouts.empty() ? "numjobs" : "nrfiles",
         fmt::format("the jobs and fio's layout of their files (a task per file laid out) would be {:.0f} tasks, more than the {} a run may "
                     "have{}",
                     tasks, limits.max_tasks, limits_hint(limits)));
}

// The layouts as an application of their own, which the jobs start after ("" if nothing is
// laid out).
std::string add_layout_app(std::vector<TaskSpec> tasks, const FioJobFile& jobs, const FioPlace& place, const std::vector<std::string>& names,
                           Scenario& s, Origins& origins) {
  if (tasks.empty()) return {};
  AppSpec app;
  app.name = "layout";
  while (std::find(names.begin(), names.end(), app.name) != names.end()) app.name += "#";
  app.host = place.host;
  app.tasks = std::move(tasks);
  const Origin origin = Origin::elsewhere(fmt::format("{}: fio's layout of the jobs' files", jobs.path));
  origins.apps.push_back(origin);
  origins.app_tasks.emplace_back(app.tasks.size(), origin);
  s.apps.push_back(std::move(app));
  return s.apps.back().name;
}

// Each job as an application of one task "io" (after `first`, the layouts of a job in a memory
// cgroup: fio runs whole in it), and as fio.json will name it.
void add_jobs(const FioJobFile& jobs, const FioPlace& place, const std::vector<Region>& regions, const std::vector<std::string>& names,
              const std::string& layout, std::vector<TaskSpec> first, Scenario& s, Origins& origins) {
  for (std::size_t i = 0; i < jobs.jobs.size(); ++i) {
    const FioJob& job = jobs.jobs[i];
    AppSpec app;
    app.name = names[i];
    app.host = place.host;
    app.memory_max = place.limits.max;
    app.memory_high = place.limits.high;
    for (const std::size_t before : job.after) app.after.push_back(names[before]);
    if (app.after.empty() && !layout.empty()) app.after.push_back(layout);
    app.tasks = std::move(first);
    first.clear();
    TaskSpec& task = app.tasks.emplace_back();
    task.name = "io";
    task.chunk_size = 100'000'000;  // an application's default (it reads no whole file)
    for (const std::string& name : job.files) task.accesses.push_back(access_of(job, i, name, regions[i]));
    task.fsync = writes(job.rw) && (job.end_fsync || job.fsync_on_close);
    task.direct_io = job.direct;
    if (job.unlink) task.deletes = job.files;
    const std::int64_t ios = std::accumulate(task.accesses.begin(), task.accesses.end(), std::int64_t{0},
                                             [](std::int64_t n, const AccessSpec& a) { return n + a.count * a.repeat; });
    s.fio.jobs.push_back(FioJobInfo{.app = app.name,
                                    .jobname = job.name,
                                    .groupid = job.group,
                                    .read_ios = writes(job.rw) ? 0 : ios,
                                    .write_ios = writes(job.rw) ? ios : 0,
                                    .options = job.own_options});
    origins.apps.push_back(Origin::elsewhere(place_of(jobs, job)));
    origins.app_tasks.emplace_back(app.tasks.size(), Origin::elsewhere(place_of(jobs, job)));
    s.apps.push_back(std::move(app));
  }
}

}  // namespace

void read_fio(TomlReader& r, const std::string& file, const ScenarioLimits& limits, Scenario& s, Origins& origins) {
  const toml::table* table = r.optional_table("fio");
  if (table == nullptr) return;
  TomlReader fr(*table, "fio", file);
  for (const char* other : {"pipelines", "apps", "workflow"}) {
    if (r.has(other)) fr.fail_table(fmt::format("a fio job file is the workload: [{}] cannot come with it", other));
  }
  const std::string path = relative_path(file, fr.required_string("file"));
  const FioPlace place = place_of_run(fr, s);
  fr.finish();
  FioJobFile jobs;
  try {
    FioLimits fio_limits;
    fio_limits.max_jobs = std::min(fio_limits.max_jobs, limits.max_tasks);
    fio_limits.max_files = limits.max_files;
    fio_limits.hint = limits_hint(limits);
    jobs = read_fio_job_file(path, fio_limits);
  } catch (const ConfigError& e) {
    if (e.place().file.empty()) fr.fail("file", e.what());
    throw;
  }
  for (std::string& w : jobs.warnings) s.warnings.push_back(std::move(w));
  if (place.limits.max > 0 && jobs.jobs.size() > 1) {
    fr.fail("memory_max", fmt::format("{} jobs in one memory cgroup are not modelled yet (one job is: its application's group)", jobs.jobs.size()));
  }
  s.fio.file = path;
  s.fio.global_options = jobs.global_options;
  const FileUse use = add_files(fr, jobs, place, s, origins);
  const std::vector<Layout> planned = layouts_of(jobs, use);
  check_task_count(jobs, planned, limits);
  const std::vector<std::string> names = app_names(jobs);
  // In a memory cgroup (one job) the layouts are the job's first tasks: its group is fio's.
  std::vector<TaskSpec> layouts = layout_tasks(planned);
  const bool in_group = place.limits.max > 0;
  const std::string layout = in_group ? std::string() : add_layout_app(std::move(layouts), jobs, place, names, s, origins);
  add_jobs(jobs, place, use.regions, names, layout, in_group ? std::move(layouts) : std::vector<TaskSpec>{}, s, origins);
}

}  // namespace pagecache::scenario
