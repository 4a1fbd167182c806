#pragma once
// Reading fio job files (fio 3.33, Debian bookworm's) into the jobs they define, for pcsim to
// simulate. The reader follows fio's rules where they are well defined, its quirks that change
// numbers included (k is 1024 and KiB is 1000 under kb_base=1024; ';' and '#' start
// a comment anywhere; a section named global* is global). Where fio silently reads bad input
// as something a simulation would get wrong (whitespace around '=', runtime=10sec read as 10 us,
// 1.5k read as 1, 150% read as a huge size) the reader refuses it with a ConfigError instead.
// Options that cannot change what pcsim computes (reports, logs, CPU placement) are ignored
// with a warning; every other option fio knows is refused as not modelled.
//
// Sizes are bytes (std::int64_t), times seconds (double).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pagecache::formats::fio {

enum class FioRw { Read, Write, RandRead, RandWrite, ReadWrite, RandReadWrite };
enum class FioFileService { RoundRobin, Sequential, Random };
/// fadvise_hint=0 (None), 1 (Auto, the default: random or sequential after rw), sequential, random.
enum class FioFadvise { None, Auto, Sequential, Random };

/// One job as fio runs it: a job section, or one of its numjobs clones.
struct FioJob {
  std::string section;        ///< the section name ($jobname, generated file names)
  std::string name;           ///< the reported name: name= if given in the job's own section, else section
  int jobnum = 0;             ///< clone index: 0 for the original, then numjobs-1 ... 1 (fio's order)
  int numjobs = 1;            ///< how many jobs its section made (the original and its clones)
  int group = 0;              ///< reporting group id (stonewall / new_group start a new one)
  int line = 0;               ///< the section header's line in its file
  /// Indices into FioJobFile::jobs that must have ended before it starts, ascending. stonewall:
  /// every job before the latest stonewall at or before it (fio's start loop stops there);
  /// wait_for: the named job and its clones.
  std::vector<std::size_t> after;
  FioRw rw = FioRw::Read;
  /// The ":N" of rw: random modes, a new random offset every N I/Os (N>=1, default 1);
  /// sequential modes, bytes added to each next offset (may be negative; default 0).
  std::int64_t rw_step = 0;
  int rwmixread = 50;         ///< percent of mixed I/O that reads
  std::int64_t bs_read = 4096, bs_write = 4096;
  std::vector<std::string> files;  ///< resolved names, directory prefixed, in order (at least one)
  bool files_given = false;   ///< from filename= (shared by clones) rather than generated
  std::int64_t size = 0;      ///< size= in bytes per job (0: not given); size_percent for N%
  int size_percent = 0;
  std::int64_t filesize = 0;  ///< 0: not given (a lo-hi range is refused for now)
  std::int64_t offset = 0;
  int offset_percent = 0;
  std::int64_t offset_increment = 0;
  int offset_increment_percent = 0;
  std::int64_t io_size = 0;   ///< 0: not given; io_size_percent for N%
  int io_size_percent = 0;
  std::int64_t number_ios = 0;
  FioFileService file_service = FioFileService::RoundRobin;
  std::int64_t file_service_step = 1;
  bool direct = false, invalidate = true, pre_read = false, create_on_open = false, overwrite = false, unlink = false;
  std::int64_t fsync = 0, fdatasync = 0;
  bool end_fsync = false, fsync_on_close = false;
  std::int64_t loops = 1;
  double runtime = 0.0, ramp_time = 0.0, startdelay = 0.0;  ///< seconds; runtime 0: none
  bool time_based = false;    ///< false when runtime is 0 (fio drops it with a warning)
  double thinktime = 0.0;     ///< seconds
  std::int64_t thinktime_blocks = 1;
  bool randrepeat = true;
  std::uint64_t randseed = 0x89;
  bool randseed_given = false;
  bool norandommap = false;
  FioFadvise fadvise = FioFadvise::Auto;
  std::string ioengine = "psync";
  std::int64_t iodepth = 1;
  /// key, raw value (after ${VAR}) as written in the job's own section, in file order (fio's
  /// JSON "job options"); a bare flag has the value "".
  std::vector<std::pair<std::string, std::string>> own_options;
};

struct FioJobFile {
  std::string path;
  std::vector<FioJob> jobs;   ///< in fio's creation order, clones right after their job
  std::vector<std::pair<std::string, std::string>> global_options;  ///< fio's JSON "global options"
  /// Options ignored because they cannot change what pcsim computes, and fio's own notes
  /// (iodepth capped at 1, time_based without runtime), each naming file:line and option, once
  /// per option.
  std::vector<std::string> warnings;
};

/// What a job file may make at most; past a limit the reader refuses it (hostile input ends
/// quickly and in bounded memory). A scenario's [fio] reads with the run's own limits on tasks
/// and files (loader_fio.cpp), checked on the declared counts before a name is made.
struct FioLimits {
  std::int64_t max_jobs = 100'000;           ///< jobs in all, clones included
  /// Files the jobs name in all: nrfiles x numjobs generated, filename= entries once per
  /// section (ScenarioLimits::max_files when read for a run).
  std::int64_t max_files = 2'000'000;
  /// Said after a limit's figure: how to lift it (" without --force"), or nothing.
  std::string hint;
  /// File names, `after` entries and own options over all jobs (clones copy theirs).
  std::int64_t max_entries = 20'000'000;
  int max_include_depth = 16;
  int max_includes = 1'000;                  ///< include lines followed in all
};

/// ${VAR} lookup: the variable's value, or nullopt if it is unset.
using FioEnvironment = std::function<std::optional<std::string>(const std::string&)>;

/// Reads fio job file text (`path` names it in errors and resolves include= relative paths);
/// `env` looks up ${VAR}. Throws ConfigError naming path:line and the option; no partial result.
FioJobFile read_fio_job_file(std::string_view text, const std::string& path, const FioEnvironment& env,
                             const FioLimits& limits = {});

/// Reads the file at `path` (read_text_file's limits) with the process environment.
FioJobFile read_fio_job_file(const std::string& path, const FioLimits& limits = {});

}  // namespace pagecache::formats::fio
