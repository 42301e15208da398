#include "toolbox/assess/gnuplot_figure.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/io/output_file.hpp"
#include "common/plot/gnuplot.hpp"

namespace ldv::assess {
namespace fs = std::filesystem;

GnuplotFigure::GnuplotFigure(std::string dir, std::string stem, int width_px, int height_px)
    : dir_(std::move(dir)), stem_(std::move(stem)), width_px_(width_px), height_px_(height_px) {}

std::string GnuplotFigure::add_data(const std::vector<std::vector<double>>& columns) {
  const std::string name = stem_ + "_" + std::to_string(blocks_++) + ".dat";
  std::FILE* f = std::fopen((fs::path(dir_) / name).c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + name);
  const size_t rows = columns.empty() ? 0 : columns[0].size();
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns.size(); ++c) std::fprintf(f, c ? " %.10g" : "%.10g", columns[c][r]);
    std::fputc('\n', f);
  }
  std::fclose(f);
  return name;
}

std::string GnuplotFigure::render() {
  const std::string png = stem_ + ".png", gp = stem_ + ".gp";
  {
    std::ofstream s(fs::path(dir_) / gp);
    s << "set terminal pngcairo size " << width_px_ << "," << height_px_ << " font 'DejaVu Sans,10'\n"
      << "set output " << plot::gnuplot_literal(png) << "\nset grid lc rgb '#dddddd'\nset key outside right top\nset border lw 0.8\n"
      << script_;
    close_checked(s, (fs::path(dir_) / gp).string());
  }
  const int rc = plot::run_gnuplot(gp, dir_, stem_ + ".log");
  std::error_code ec;
  const auto size = fs::file_size(fs::path(dir_) / png, ec);
  if (rc != 0 || ec || size == 0) {
    std::ifstream log(fs::path(dir_) / (stem_ + ".log"));
    std::string msg((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    throw std::runtime_error("gnuplot failed on " + gp + ": " + msg);
  }
  fs::remove(fs::path(dir_) / (stem_ + ".log"), ec);
  return png;
}

std::vector<size_t> thin_indices(size_t n, size_t max_points) {
  std::vector<size_t> idx;
  const size_t step = n > max_points ? (n + max_points - 1) / max_points : 1;
  for (size_t i = 0; i < n; i += step) idx.push_back(i);
  if (n > 0 && idx.back() != n - 1) idx.push_back(n - 1);
  return idx;
}

}  // namespace ldv::assess
