#pragma once
// `pcsim validate --here`: the paper's experiments run for real on this machine (Exp-1-like
// single pipelines at three sizes against free memory, Exp-2-like concurrent pipelines),
// simulated on the machine's calibrated platform, and compared with the paper's metric:
// per-phase |pcsim - real| / real against the mean of the repetitions, with the repetitions'
// own spread beside it. The measurements are kept as files, so that a later pcsim can score
// them again without running any I/O.

#include "calibrate/real_run.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace pagecache::validate {

/// What a validation on a machine measured: its platform and every real run.
struct HereMeasurements {
  std::string platform_toml;
  std::vector<calibrate::RealRun> runs;  ///< cases in order, each case's repetitions together
};

/// The cases, sized against `available` bytes of memory (MemAvailable): Exp-1-like single
/// pipelines with files of 8, 20 and 40 % of it (from fitting in the cache to exceeding it,
/// as the paper's 20 to 100 GB on 250 GiB), Exp-2-like 4 and 8 pipelines of 1.2 % each (the
/// paper's 3 GB); with `quick`, one tiny case of each kind (64 MiB, and 2 x 32 MiB).
std::vector<calibrate::RealCase> here_cases(std::int64_t available, bool quick);

/// The measurements as files (name, text): platform.toml, runs.csv, phases.csv, memory.csv.
std::vector<std::pair<std::string, std::string>> here_files(const HereMeasurements& m);
/// Reads them back from a folder here_files' files were written to, as strictly as
/// here_data.hpp says. Throws ConfigError naming the file, line and column of any fault.
HereMeasurements load_here(const std::filesystem::path& folder);

/// Simulates every case on the platform and compares: the printable tables.
std::string score_here(const HereMeasurements& m);

}  // namespace pagecache::validate
