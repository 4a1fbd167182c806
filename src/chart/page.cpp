#include "chart/page.hpp"

#include "chart/html_text.hpp"

namespace pagecache::chart {

namespace {

constexpr std::string_view kStyle = R"(body{font-family:system-ui,-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;margin:24px;color:#222;max-width:1000px}
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:2em}
table{border-collapse:collapse;font-size:0.9em}th,td{padding:3px 10px;border-bottom:1px solid #ddd}
th{text-align:left;background:#f4f4f4}td.num{text-align:right;font-variant-numeric:tabular-nums}
p.note{color:#555;font-size:0.9em}
svg.chart{display:block;margin:8px 0;font-size:12px;background:#fff}
svg.chart text{fill:#222}svg.chart .axis-title{font-size:13px}
svg.chart .grid{stroke:#e4e4e4;stroke-width:1}svg.chart .tick-mark{stroke:#555}
svg.chart .frame{fill:none;stroke:#555;stroke-width:1}
svg.chart path.series{stroke:#333;stroke-width:0.3}svg.chart path.series.line{stroke-width:1.5}
footer{margin-top:3em;color:#777;font-size:0.85em}
)";

}  // namespace

std::string html_page(std::string_view title, std::string_view body) {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<title>" + escape(title) + "</title>\n<style>\n";
  out += kStyle;
  out += "</style>\n</head>\n<body>\n";
  out += body;
  return out + "</body>\n</html>\n";
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table>\n<tr>";
  for (const std::string& h : header) out += "<th>" + escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (std::size_t i = 0; i < row.size(); ++i) out += (i == 0 ? "<td>" : "<td class=\"num\">") + escape(row[i]) + "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

}  // namespace pagecache::chart
