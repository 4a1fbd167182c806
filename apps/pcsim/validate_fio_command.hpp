#pragma once
// `pcsim validate --here --fio JOB.fio ...`: fio job files run with the real fio on this machine
// (calibrate/real_fio.hpp), kept in --out (validate/fio_kept.hpp) and scored against pcsim's
// simulation of them on the machine's platform (validate/fio_score.hpp); `--from` a folder of
// such measurements scores them again without fio.

#include "validate_here_command.hpp"

#include <string>

namespace pcsim {

/// --here --fio: every job file checked by pcsim first (a refused one stops everything before
/// anything runs), the platform got, each job file run --repeat times, kept, scored: the
/// table printed and written to fio-scores.json. Returns 0 once scored, whatever the verdicts.
int run_validate_fio(const ValidateHereOptions& options);
/// --from a folder of fio measurements: the same table, simulating again.
int score_validate_fio(const std::string& folder);

}  // namespace pcsim
