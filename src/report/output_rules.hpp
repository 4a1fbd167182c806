#pragma once
// Which folders `pcsim run --out` may replace. pcsim marks every output folder it makes with a
// file .pcsim-output and replaces a folder only if it is empty, or holds that marker and none
// but pcsim's own output files. Anything else (a file, a symbolic link, a folder holding what
// pcsim did not write, the current folder or one above it, a mount point) is refused before
// anything is removed, and there is no override: pcsim never deletes what it did not write.

#include <filesystem>
#include <optional>
#include <string>

namespace pagecache::report {

inline constexpr const char* kMarkerName = ".pcsim-output";
/// Fixed, so that the outputs of two runs of one scenario stay byte-identical.
inline constexpr const char* kMarkerText = "written by pcsim; pcsim run --out may replace this folder\n";

/// The names pcsim writes into an output folder (outputs.cpp), the marker included: the only
/// names it ever deletes.
inline constexpr const char* kOutputNames[] = {"timeline.csv", "memory.csv", "cache.csv", "summary.json", "timing.json", "report.html",
                                               "trace.json", "fio.json", kMarkerName};

/// The absolute path of the folder `--out dir` names: links in the folders above it resolved,
/// its own last name never followed ("." and ".." name the folder they lead to). Throws
/// ConfigError if `dir` is empty.
std::filesystem::path output_folder_path(const std::string& dir);

/// Why pcsim may not put its outputs in place of `path` (to follow "it": "holds 'src', which
/// pcsim did not write"), or nothing if it may: `path` is absent, an empty folder, or a folder
/// of pcsim's that does not hold `scenario_file` (if given). Decided from what is there now;
/// the entry named is the first in byte order.
std::optional<std::string> refusal(const std::filesystem::path& path, const std::string& scenario_file = {});

/// Why pcsim could not replace the folder `path` that refusal() allows, though it may: it, or
/// one of pcsim's files in it, is immutable or append-only. Nothing if it can, or is absent.
std::optional<std::string> cannot_replace(const std::filesystem::path& path);

/// Throws ConfigError for `--out dir`, naming the folder and the reason.
[[noreturn]] void refuse(const std::string& dir, const std::filesystem::path& path, const std::string& reason);

/// The check before simulating: throws ConfigError (see refuse) if `--out dir` may not receive
/// the outputs, or if it holds `scenario_file` (empty: the embedded default). OutputFolder
/// checks again when it commits.
void check_output_folder(const std::string& dir, const std::string& scenario_file);

}  // namespace pagecache::report
