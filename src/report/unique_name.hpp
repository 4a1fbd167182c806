#pragma once
// Fresh names next to an output, for staging folders, temporary files and folders set aside:
// what mkdtemp and mkstemp do, but with the permissions the umask gives (theirs are 0700 and
// 0600, which the renamed result would keep).

#include <filesystem>
#include <functional>
#include <string>

namespace pagecache::report {

/// Makes "<stem>-<pid>-<8 random hex digits>" in `folder` with `create`, which must create the
/// path exclusively (mkdir, open with O_EXCL) and return false if it exists already, or throw;
/// tries other names until one is free. Returns the path made.
std::filesystem::path create_unique(const std::filesystem::path& folder, const std::string& stem,
                                    const std::function<bool(const std::filesystem::path&)>& create);

/// create_unique for an empty folder (mode 0777 less the umask). Throws Error if it fails.
std::filesystem::path create_unique_folder(const std::filesystem::path& folder, const std::string& stem);

/// Whether pcsim may make a file (or, `as_folder`, a folder) in `folder` now: 0, or the errno
/// that refused it. Tried with one made under a fresh ".pcsim.tmp" name and removed at once,
/// signals held: root passes access() where nothing can be made (/proc, a read-only mount).
int probe_folder(const std::filesystem::path& folder, bool as_folder);

}  // namespace pagecache::report
