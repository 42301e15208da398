#include "toolbox/allan/allan_plot.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "common/io/output_file.hpp"
#include "common/plot/gnuplot.hpp"

namespace ldv::allan {
namespace {

const ModelTerm kPlotTerms[] = {ModelTerm::kQ, ModelTerm::kN, ModelTerm::kB, ModelTerm::kK, ModelTerm::kR,
                                ModelTerm::kGaussMarkov, ModelTerm::kSinusoid};

// A dense tau grid over the data range for the model curves.
std::vector<double> model_grid(const ChannelResult& r) {
  std::vector<double> g;
  if (r.oadev.empty()) return g;
  const double a = std::log10(r.oadev.front().point.tau_s), b = std::log10(r.oadev.back().point.tau_s);
  for (int i = 0; i <= 200; ++i) g.push_back(std::pow(10.0, a + (b - a) * i / 200.0));
  return g;
}

}  // namespace

void plot_allan(const std::string& png, const std::vector<ChannelResult>& results) {
  const std::string dat = png + ".dat", gp = png + ".gp";
  std::ofstream d(dat);
  if (!d) throw std::runtime_error("cannot write " + dat);
  d.precision(10);
  // Two gnuplot data blocks per channel: measured points, then model curves.
  for (const ChannelResult& r : results) {
    d << "# " << r.name << " measured: tau_s oadev lo hi\n";
    for (const auto& p : r.oadev) d << p.point.tau_s << ' ' << p.point.dev << ' ' << p.interval.lo << ' ' << p.interval.hi << '\n';
    d << "\n\n# " << r.name << " model: tau_s total Q N B K R GM sine (Allan deviation of each term)\n";
    for (double tau : model_grid(r)) {
      d << tau << ' ' << (r.fit ? std::sqrt(r.fit->model_avar(tau)) : 0.0);
      for (ModelTerm t : kPlotTerms) {
        double v = 0.0;
        if (r.fit) {
          const TermEstimate& e = (*r.fit)[t];
          if (e.in_model && e.value > 0) v = e.value * std::sqrt(term_avar(t, tau, e.shape));
        }
        d << ' ' << v;
      }
      d << '\n';
    }
    d << "\n\n";
  }
  close_checked(d, dat);
  const size_t n = results.size();
  const int cols = n <= 1 ? 1 : (n <= 4 ? 2 : 3);
  const int rows = static_cast<int>((n + cols - 1) / cols);
  std::ofstream g(gp);
  if (!g) throw std::runtime_error("cannot write " + gp);
  g << "# ldv allan plot; re-run with: gnuplot " << gp << "\n"
    << "set terminal pngcairo size " << 640 * cols << "," << 480 * rows << " noenhanced\n"
    << "set output " << plot::gnuplot_literal(png) << "\n"
    << "set logscale xy\nset grid xtics ytics mxtics mytics\nset format y '%.0e'\nset key bottom left font ',8'\n"
    << "set xlabel 'tau [s]'\n";
  if (n > 1) g << "set multiplot layout " << rows << "," << cols << "\n";
  const char* names[] = {"Q", "N", "B", "K", "R", "GM", "sine"};
  for (size_t c = 0; c < n; ++c) {
    const ChannelResult& r = results[c];
    g << "set title " << plot::gnuplot_literal(r.name) << "\nset ylabel "
      << plot::gnuplot_literal("Allan deviation [" + r.unit + "]") << "\n";
    g << "plot " << plot::gnuplot_literal(dat) << " index " << 2 * c << " using 1:2:3:4 with yerrorbars pt 7 ps 0.5 lc rgb 'black' title 'OADEV (68% CI)'";
    if (r.fit) {
      g << ", '' index " << 2 * c + 1 << " using 1:2 with lines lw 2 lc rgb 'red' title 'fit total'";
      for (int k = 0; k < 7; ++k) {
        const TermEstimate& e = (*r.fit)[kPlotTerms[k]];
        if (e.in_model && e.value > 0) {
          g << ", '' index " << 2 * c + 1 << " using 1:($" << 3 + k << ">0?$" << 3 + k << ":1/0) with lines dt 2 title '"
            << names[k] << "'";
        }
      }
    }
    g << "\n";
  }
  if (n > 1) g << "unset multiplot\n";
  close_checked(g, gp);
  if (plot::run_gnuplot(gp, ".") != 0) throw std::runtime_error("gnuplot failed on " + gp);
}

}  // namespace ldv::allan
