#pragma once
// The HTML page around the charts: one self-contained file (inline CSS, inline SVG, no script,
// no link to anything), readable offline from file://.

#include <string>
#include <string_view>
#include <vector>

namespace pagecache::chart {

/// A whole HTML document: `title` (escaped here) and `body` (HTML already).
std::string html_page(std::string_view title, std::string_view body);

/// A table: a header row and rows of cells, every cell escaped here. Cells of the columns
/// after the first are right-aligned (figures).
std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

}  // namespace pagecache::chart
