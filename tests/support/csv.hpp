#pragma once
// The validation data's CSV reader, for tests, and where the data is.

#include "validate/csv.hpp"

#include <string>

namespace pagecache::testing {

using validate::CsvRow;
using validate::read_csv;

inline std::string validation_file(const std::string& name) { return std::string(PAGECACHE_VALIDATION_DIR) + "/" + name; }

}  // namespace pagecache::testing
