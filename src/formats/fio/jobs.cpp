// From sections to jobs as fio makes them (init.c get_new_job, add_job): each job section
// starts from the global template as it stands at its header, numjobs clones follow their job
// (jobnum 0, then numjobs-1 ... 1), files are named or generated, reporting groups and the
// start order (stonewall, wait_for) are worked out.

#include "formats/fio/job_file.hpp"
#include "formats/fio/options.hpp"
#include "formats/fio/syntax.hpp"
#include "formats/common/text_file.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace pagecache::formats::fio {

namespace {

using fio::Draft;
using fio::RawSection;

struct Builder {
  const std::string& path;
  const FioLimits& limits;
  FioJobFile& out;
  fio::Warnings& warnings;
  int group = 0;
  std::int64_t group_jobs = 0;  // jobs in the current group (init.c prev_group_jobs)
  std::size_t barrier = 0;      // jobs before the latest stonewall wait for it
  std::int64_t entries = 0;     // files, after entries and own options over all jobs
  std::int64_t files_named = 0;  // file names made so far (clones' generated ones each)

  [[noreturn]] void fail(const RawSection& s, const std::string& key, const std::string& message) const {
    throw ConfigError(fio::where(path, s.line) + message, InputPlace{.file = path, .line = s.line, .key = key});
  }
  void check(Draft& d, const RawSection& s);
  std::vector<std::size_t> waitees(const Draft& d, const RawSection& s) const;
  std::vector<std::string> generated_files(const Draft& d, int jobnum, const RawSection& s) const;
  void add(Draft d, const RawSection& s);
};

bool reads(FioRw rw) { return rw != FioRw::Write && rw != FioRw::RandWrite; }

// What fio checks or changes once a job's options are all read (init.c fixup_options).
void Builder::check(Draft& d, const RawSection& s) {
  FioJob& job = d.job;
  job.time_based = d.time_based_asked && job.runtime > 0.0;
  if (d.time_based_asked && job.runtime <= 0.0) {
    warnings.add("time_based", fmt::format("{}job '{}': time_based without runtime is dropped, as fio does", fio::where(path, s.line), s.name));
  }
  if (job.iodepth > 1) {
    warnings.add("iodepth", fmt::format("{}job '{}': iodepth={} with the synchronous engine {}: fio caps it at 1, and so does pcsim",
                                        fio::where(path, s.line), s.name, job.iodepth, job.ioengine));
  }
  // fio: a job that reads lays out its files with data first; pre-reading replaces invalidating.
  if (reads(job.rw)) job.overwrite = true;
  if (job.pre_read) job.invalidate = false;
  // fio.h td_min_bs: the smallest of the read, write and trim sizes, whatever the job does.
  const std::int64_t min_bs = std::min({job.bs_read, job.bs_write, d.bs_trim});
  if (job.size > 0 && job.size < min_bs) {
    fail(s, "size", fmt::format("job '{}': size={} is smaller than the block size ({} bytes; fio: size too small)", s.name, job.size, min_bs));
  }
}

// The waitee of wait_for and its clones (init.c wait_for_ok: an earlier job, named once).
std::vector<std::size_t> Builder::waitees(const Draft& d, const RawSection& s) const {
  if (d.wait_for.empty()) return {};
  if (d.wait_for == s.name || d.wait_for == d.job.name) fail(s, "wait_for", fmt::format("job '{}' cannot wait for itself (wait_for={})", s.name, d.wait_for));
  std::vector<std::size_t> originals;
  for (std::size_t i = 0; i < out.jobs.size(); ++i) {
    if (out.jobs[i].jobnum == 0 && out.jobs[i].name == d.wait_for) originals.push_back(i);
  }
  if (originals.empty()) {
    fail(s, "wait_for", fmt::format("job '{}': wait_for={} names no job defined before it (fio: waitee job unknown)", s.name, d.wait_for));
  }
  if (originals.size() > 1) {
    fail(s, "wait_for", fmt::format("job '{}': wait_for={} is ambiguous: {} jobs have that name", s.name, d.wait_for, originals.size()));
  }
  std::vector<std::size_t> list;
  const FioJob& waitee = out.jobs[originals.front()];
  for (int k = 0; k < waitee.numjobs; ++k) list.push_back(originals.front() + static_cast<std::size_t>(k));
  return list;
}

// filename_format's keywords, matched in any case (init.c make_filename).
std::string format_name(const std::string& format, const std::string& jobname, int jobnum, std::int64_t filenum) {
  if (format.empty()) return fmt::format("{}.{}.{}", jobname, jobnum, filenum);
  std::string out;
  for (std::size_t i = 0; i < format.size();) {
    auto at = [&](std::string_view word) {
      if (format.size() - i < word.size()) return false;
      for (std::size_t k = 0; k < word.size(); ++k) {
        if (std::tolower(static_cast<unsigned char>(format[i + k])) != word[k]) return false;
      }
      return true;
    };
    if (at("$jobname")) out += jobname, i += 8;
    else if (at("$jobnum")) out += std::to_string(jobnum), i += 7;
    else if (at("$filenum")) out += std::to_string(filenum), i += 8;
    else out += format[i++];
  }
  return out;
}

// Generated files go to directory jobnum mod ndirs (options.c set_name_idx).
std::vector<std::string> Builder::generated_files(const Draft& d, int jobnum, const RawSection& s) const {
  std::vector<std::string> files;
  files.reserve(static_cast<std::size_t>(d.nrfiles));
  const std::string prefix = d.directories.empty() ? std::string() : d.directories[static_cast<std::size_t>(jobnum) % d.directories.size()] + "/";
  for (std::int64_t i = 0; i < d.nrfiles; ++i) {
    files.push_back(prefix + format_name(d.filename_format, s.name, jobnum, i));
    if (files.back().size() > 4095) fail(s, "filename_format", fmt::format("job '{}': the file name '{}' is longer than 4095 bytes", s.name, files.back()));
  }
  return files;
}

void Builder::add(Draft d, const RawSection& s) {
  check(d, s);
  if (static_cast<std::int64_t>(out.jobs.size()) + d.numjobs > limits.max_jobs) {
    fail(s, "numjobs", fmt::format("job '{}': more than {} jobs in all, clones included", s.name, limits.max_jobs));
  }
  if ((d.stonewall || d.new_group) && group_jobs > 0) ++group, group_jobs = 0;
  group_jobs += d.numjobs;
  if (d.stonewall) barrier = out.jobs.size();
  std::vector<std::size_t> after(barrier);
  for (std::size_t i = 0; i < barrier; ++i) after[i] = i;
  for (std::size_t i : waitees(d, s)) {
    if (i >= barrier) after.push_back(i);
  }
  const bool given = !d.explicit_files.empty();
  const std::int64_t files = given ? static_cast<std::int64_t>(d.explicit_files.size()) : d.nrfiles;
  const auto cost = static_cast<double>(d.numjobs) * static_cast<double>(files + static_cast<std::int64_t>(after.size() + d.job.own_options.size()));
  if (static_cast<double>(entries) + cost > static_cast<double>(limits.max_entries)) {
    fail(s, "numjobs", fmt::format("job '{}': the jobs would hold more than {} file names, orderings and options in all", s.name, limits.max_entries));
  }
  entries += static_cast<std::int64_t>(cost);
  // The run's limit on files, on the declared counts: generated names are each clone's own.
  const double named = given ? static_cast<double>(files) : static_cast<double>(d.numjobs) * static_cast<double>(files);
  if (static_cast<double>(files_named) + named > static_cast<double>(limits.max_files)) {
    fail(s, given ? "filename" : d.nrfiles == 1 ? "numjobs" : "nrfiles",
         fmt::format("job '{}': the jobs would name {:.0f} files, more than the {} a run may have{}", s.name,
                     static_cast<double>(files_named) + named, limits.max_files, limits.hint));
  }
  files_named += static_cast<std::int64_t>(named);
  d.job.numjobs = static_cast<int>(d.numjobs);
  d.job.after = std::move(after);
  d.job.files_given = given;
  if (given) d.job.files = std::move(d.explicit_files);
  for (std::int64_t k = 0; k < d.numjobs; ++k) {
    const int jobnum = k == 0 ? 0 : static_cast<int>(d.numjobs - k);
    FioJob& job = out.jobs.emplace_back(d.job);
    job.jobnum = jobnum;
    job.group = group;
    if (!given) job.files = generated_files(d, jobnum, s);
  }
}

}  // namespace

FioJobFile read_fio_job_file(std::string_view text, const std::string& path, const FioEnvironment& env, const FioLimits& limits) {
  const std::vector<RawSection> sections = fio::read_sections(text, path, env, limits);
  FioJobFile out;
  out.path = path;
  fio::Warnings warnings;
  Builder builder{.path = path, .limits = limits, .out = out, .warnings = warnings};
  Draft global;
  global.limits = &limits;
  for (const RawSection& section : sections) {
    std::vector<std::pair<std::string, std::string>> raw;
    for (const fio::RawOption& o : section.options) raw.emplace_back(o.key, o.value);
    if (section.global) {
      fio::apply_options(global, section.options, warnings);
      out.global_options.insert(out.global_options.end(), raw.begin(), raw.end());
      continue;
    }
    // A job starts from the template as it stands now; its own section name replaces an
    // inherited name= (init.c get_new_job).
    Draft draft = global;
    draft.job.section = section.name;
    draft.job.name = section.name;
    draft.job.line = section.line;
    draft.job.own_options = std::move(raw);
    fio::apply_options(draft, section.options, warnings);
    builder.add(std::move(draft), section);
  }
  if (out.jobs.empty()) throw ConfigError(fmt::format("{}: no jobs defined (fio: No job(s) defined)", path), InputPlace{.file = path, .line = 0, .key = {}});
  out.warnings = std::move(warnings.list);
  return out;
}

FioJobFile read_fio_job_file(const std::string& path, const FioLimits& limits) {
  const std::string text = read_text_file(path, "fio job file");
  return read_fio_job_file(
      text, path,
      [](const std::string& name) -> std::optional<std::string> {
        const char* value = std::getenv(name.c_str());
        if (value == nullptr) return std::nullopt;
        return std::string(value);
      },
      limits);
}

}  // namespace pagecache::formats::fio
