#include "toolbox/assess/html_page.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "common/io/output_file.hpp"

namespace ldv::assess {

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

void HtmlPage::section(const std::string& heading) { body_ += "<h2>" + html_escape(heading) + "</h2>\n"; }

void HtmlPage::paragraph(const std::string& text) { body_ += "<p>" + html_escape(text) + "</p>\n"; }

void HtmlPage::table(const HtmlTable& t) {
  body_ += "<table>";
  if (!t.caption.empty()) body_ += "<caption>" + html_escape(t.caption) + "</caption>";
  body_ += "<tr>";
  for (const auto& h : t.header) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& r : t.rows) {
    body_ += "<tr>";
    for (const auto& c : r) body_ += "<td>" + html_escape(c) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void HtmlPage::figure(const std::string& png, const std::string& caption, const std::vector<HtmlTable>& tables) {
  body_ += "<div class=\"row\"><figure><img src=\"" + html_escape(png) + "\" alt=\"" + html_escape(caption) +
           "\"><figcaption>" + html_escape(caption) + "</figcaption></figure>";
  if (!tables.empty()) {
    body_ += "<div class=\"tables\">";
    for (const auto& t : tables) table(t);
    body_ += "</div>";
  }
  body_ += "</div>\n";
}

std::string HtmlPage::str() const {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + html_escape(title_) +
         "</title>\n<style>\n"
         "body{font-family:'DejaVu Sans',Arial,sans-serif;margin:24px;color:#222;max-width:1500px}\n"
         "h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:4px;margin-top:32px}\n"
         ".row{display:flex;flex-wrap:wrap;gap:20px;align-items:flex-start;margin:12px 0}\n"
         "figure{margin:0}img{max-width:100%;border:1px solid #eee}figcaption{font-size:12px;color:#555}\n"
         "table{border-collapse:collapse;font-size:12px;margin-bottom:12px}caption{text-align:left;font-weight:bold;padding:4px 0}\n"
         "th,td{border:1px solid #ccc;padding:3px 7px;text-align:right}th{background:#f2f2f2}\n"
         "td:first-child,th:first-child{text-align:left}\n"
         "</style></head>\n<body>\n<h1>" +
         html_escape(title_) + "</h1>\n" + body_ + "</body></html>\n";
}

void HtmlPage::write(const std::string& path) const {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << str();
  close_checked(f, path);
}

}  // namespace ldv::assess
