#pragma once
// What may name a host, disk, file, application or task, in every input format: names end up
// in CSV outputs and messages, so they are UTF-8 text without control characters or a
// spreadsheet formula's first character.

#include <string>
#include <string_view>

namespace pagecache::formats {

/// Empty if `name` can name a host, disk, file, application or task; else why not (control
/// characters, invalid UTF-8, a leading = + - @ that a spreadsheet would run as a formula).
std::string name_problem(std::string_view name);

}  // namespace pagecache::formats
