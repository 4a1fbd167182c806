#include "chart/text_width.hpp"

#include "text/utf8.hpp"

#include <array>
#include <vector>

namespace pagecache::chart {

namespace {

// DejaVu Sans advance widths of ASCII 32..126, in 1/2048 em.
constexpr std::array<int, 95> kAdvance = {
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,   // space to /
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303,                                       // 0 to 9
    690,  690,  1716, 1716, 1716, 1087, 2048,                                                         // : to @
    1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612, 1235,   // A to P
    1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403,                                       // Q to Z
    799,  690,  799,  1716, 1024, 1024,                                                               // [ to `
    1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186, 569,  1995, 1298, 1253, 1300,   // a to p
    1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075,                                       // q to z
    1303, 690,  1303, 1716};                                                                          // { to ~

// A little over the font's own widths: hinting and another font's metrics may add some.
constexpr double kSlack = 1.04;

double em_of(char32_t c) { return c >= 32 && c <= 126 ? kAdvance[c - 32] / 2048.0 : 1.0; }

struct Glyph {
  std::size_t offset;  // in bytes
  std::size_t length;
  double em;
};

std::vector<Glyph> glyphs(std::string_view s) {
  std::vector<Glyph> out;
  for (std::size_t at = 0; at < s.size();) {
    const text::Utf8Char c = text::next_utf8_char(s.substr(at));
    out.push_back({at, c.length, c.valid ? em_of(c.code_point) : 1.0});
    at += c.length;
  }
  return out;
}

}  // namespace

double text_width(std::string_view s, double font_px) {
  double em = 0.0;
  for (const Glyph& g : glyphs(s)) em += g.em;
  return em * font_px * kSlack;
}

std::string fit_text(std::string_view s, double room, double font_px) {
  if (text_width(s, font_px) <= room) return std::string(s);
  const std::vector<Glyph> g = glyphs(s);
  const double budget = room / (font_px * kSlack) - 1.0;  // the ellipsis counted as 1 em
  // Characters taken from the end and the start in turn, the end first, while they fit.
  std::size_t head = 0, tail = 0;
  double used = 0.0;
  for (bool from_end = true; head + tail < g.size(); from_end = !from_end) {
    const Glyph& next = from_end ? g[g.size() - 1 - tail] : g[head];
    if (used + next.em > budget) break;
    used += next.em;
    (from_end ? tail : head) += 1;
  }
  const std::size_t tail_at = tail == 0 ? s.size() : g[g.size() - tail].offset;
  return std::string(s.substr(0, head == 0 ? 0 : g[head].offset)) + "\u2026" + std::string(s.substr(tail_at));
}

}  // namespace pagecache::chart
