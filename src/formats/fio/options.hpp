#pragma once
// fio's options as pcsim reads them: the supported ones set a job's fields, the ones that cannot
// change what pcsim computes (reports, logs, CPU placement) are ignored with a warning, every
// other option fio knows is refused as not modelled, and a name fio does not know is refused as
// unknown (with "did you mean" when it is close to one).

#include "formats/fio/job_file.hpp"
#include "formats/fio/syntax.hpp"

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace pagecache::formats::fio {

/// A job (or the global template) while its sections' options are applied: the FioJob and what
/// fio keeps until the job is added (file naming, clones, ordering).
struct Draft {
  FioJob job;
  const FioLimits* limits = nullptr;
  int kb_base = 1024;
  std::int64_t nrfiles = 1;
  std::int64_t numjobs = 1;
  std::int64_t bs_trim = 4096;  ///< the trim slot of bs: fio's minimum block size counts it
  std::string filename_format;           ///< "" for fio's $jobname.$jobnum.$filenum
  std::vector<std::string> directories;  ///< directory=, split on ':'
  std::vector<std::string> explicit_files;  ///< filename= entries, inherited ones first, each prefixed when given
  bool stonewall = false, new_group = false;
  std::string wait_for;
  bool time_based_asked = false;  ///< time_based=1 written, before the check for runtime
};

/// Warnings, once per option key.
struct Warnings {
  std::vector<std::string> list;
  std::set<std::string> seen;
  void add(const std::string& key, const std::string& text);
};

/// Applies one section's options to `draft` in fio's order (parse.c sort_options: kb_base
/// first, filename and filename_format last, the rest as written). Throws ConfigError at the
/// first option refused.
void apply_options(Draft& draft, const std::vector<RawOption>& options, Warnings& warnings);

/// The options pcsim reads (names and aliases), for tests and the README.
std::vector<std::string> supported_option_names();

/// Ignored options: the name and why it cannot change what pcsim computes.
struct IgnoredOption {
  const char* name;
  const char* why;
  enum class Value { Any, Bool, Flag } value;
};
const std::vector<IgnoredOption>& ignored_options();

/// Every option name fio 3.33 knows (its own, its engines', its profiles'), aliases included.
const std::set<std::string>& fio_option_names();

}  // namespace pagecache::formats::fio
