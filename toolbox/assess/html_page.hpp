#pragma once
// A self-contained HTML page (inline style, no scripts or external resources besides the PNGs beside it).
#include <string>
#include <vector>

namespace ldv::assess {

struct HtmlTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

class HtmlPage {
 public:
  explicit HtmlPage(std::string title) : title_(std::move(title)) {}
  void section(const std::string& heading);
  void paragraph(const std::string& text);  // escaped
  // A plot with its tables to the right (stacked below on narrow windows).
  void figure(const std::string& png, const std::string& caption, const std::vector<HtmlTable>& tables = {});
  void table(const HtmlTable& t);
  std::string str() const;
  void write(const std::string& path) const;

 private:
  std::string title_, body_;
};

std::string html_escape(const std::string& s);
// Fixed-point text with `decimals` decimals ("-" for NaN).
std::string fixed(double v, int decimals);

}  // namespace ldv::assess
