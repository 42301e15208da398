#pragma once
// Plots through gnuplot (Debian gnuplot-nox, pngcairo terminal): each figure writes its data as text
// columns and a .gp script beside the PNG, so a reader can re-plot or restyle it by hand.
#include <string>
#include <vector>

namespace ldv::assess {

class GnuplotFigure {
 public:
  // `stem`: file name without extension inside `dir` (stem.png, stem.gp, stem_<n>.dat).
  GnuplotFigure(std::string dir, std::string stem, int width_px = 900, int height_px = 420);

  // A data block: columns of equal length; returns its file name for use in plot commands.
  std::string add_data(const std::vector<std::vector<double>>& columns);
  // Script lines after the terminal set-up (set title/xlabel/..., plot ...). Any text that comes from
  // data or users goes in through plot::gnuplot_label / gnuplot_literal (common/plot/gnuplot.hpp).
  void add(const std::string& script_line) { script_ += script_line + "\n"; }
  // Writes the script, runs gnuplot; returns the PNG file name (relative to dir). Throws std::runtime_error
  // with gnuplot's message if it fails or the PNG is empty.
  std::string render();

 private:
  std::string dir_, stem_;
  int width_px_, height_px_, blocks_ = 0;
  std::string script_;
};

// Keeps at most max_points evenly spaced indices of n (plots of long runs stay light).
std::vector<size_t> thin_indices(size_t n, size_t max_points);

}  // namespace ldv::assess
