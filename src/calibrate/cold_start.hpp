#pragma once
// A known start for a real run: the page cache dropped (as root) and, on a virtual machine
// with free page reporting, the memory that freed given back to the host, so that the run
// starts as pcsim does (free memory cold but for what the run itself frees, docs/model.md §6.16).

namespace pagecache::calibrate {

/// As root: sync, then the whole page cache dropped (/proc/sys/vm/drop_caches); false if it
/// could not be.
bool drop_all_caches();

/// Waits until the kernel's count of reported free memory has not grown over a whole
/// reporting pass (2 s apart, mm/page_reporting.c), at most `limit` seconds: true if it
/// stopped growing; false at once where it is not counted. Throws std::runtime_error if a
/// stop is requested meanwhile (SIGINT, SIGTERM).
bool wait_for_reporting(double limit);

}  // namespace pagecache::calibrate
