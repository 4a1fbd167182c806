#pragma once
// Text put into an HTML page or an SVG drawing: names come from scenario files and may hold
// anything, so every one goes through escape() before it reaches the page.

#include <cstddef>
#include <string>
#include <string_view>

namespace pagecache::chart {

/// `s` safe as HTML text and as a quoted attribute value: & < > " ' as character references,
/// control characters but tab and newline as U+FFFD, each ill-formed UTF-8 part as U+FFFD.
std::string escape(std::string_view s);

/// `value` with `decimals` digits after the point, never "-0" (coordinates and figures: fixed
/// precision keeps a page byte-identical for the same input).
std::string fixed(double value, int decimals);

}  // namespace pagecache::chart
