#pragma once
// How wide a label will be drawn, without a browser: charts size their margins and shorten
// labels by it, so that no label is clipped by the SVG's edge or drawn over another. Widths are
// DejaVu Sans's (the common sans-serif fallback and wider than Helvetica or Arial): an estimate
// that errs on the wide side for the fonts a page is likely to get.

#include <cstddef>
#include <string>
#include <string_view>

namespace pagecache::chart {

/// The font size of every chart's text but axis titles (page.cpp's style), in pixels.
inline constexpr double kFontPx = 12.0;
/// The height of a line of text at `font_px`: ascent plus descent, what a label's box spans.
inline constexpr double line_height(double font_px = kFontPx) { return font_px * 1.17; }

/// `s` drawn at `font_px`, in pixels; a code point beyond ASCII counts as 1 em (the widest).
double text_width(std::string_view s, double font_px = kFontPx);

/// `s` if it fits in `room` pixels, else its start and its end around an ellipsis ("…"), as
/// much of both as fits (the end of a task's or a file's name tells it from its siblings).
/// Not escaped (escape the result); "…" alone if even one character of each end does not fit.
std::string fit_text(std::string_view s, double room, double font_px = kFontPx);

}  // namespace pagecache::chart
