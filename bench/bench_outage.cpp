// `ldv outage` speed, and a Table 12 layout on the simulator's stand-in grades.
//   build/bin/bench_outage                         1 h of 200 Hz hg1700-typical drive, outages of 1, 2, 5, 10 min
//   build/bin/bench_outage --table12=OUT.md [--hours=1] [--model=kfgins21]
//       the stand-in grades hg1700-typical, hg1900-typical, 3dm-gx2-typical on the same land-vehicle drive,
//       Markdown table. The paper's Table 12 with the paper's own grades beside its numbers is
//       bench/paper_tables/table12.sh (docs/paper_table12.md).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "toolbox/assess/outage_run.hpp"
#include "toolbox/assess/outage_table.hpp"

namespace {
using namespace ldv;

sim::SimResult drive(const std::string& grade, double duration_s, uint64_t seed = 11) {
  sim::SimRequest req;
  req.grade = grade;
  req.duration_s = duration_s;
  req.scenario = "drive";
  req.seed = seed;
  return sim::simulate(req);
}

assess::NavSeries truth_of(const sim::SimResult& s) {
  std::vector<assess::NavSample> v;
  v.reserve(s.truth.size());
  for (const auto& t : s.truth) v.push_back({t.t_s, t.pos, t.vel_n_mps, quat_from_euler(t.rpy_rad)});
  return assess::NavSeries(std::move(v));
}

assess::OutageRun outages(const sim::SimResult& s, const std::string& model) {
  est::FilterOptions fo = est::options_from_kfgins(s.kfgins);
  if (!model.empty()) fo.model = model;
  return assess::run_outages(s.imu, s.gnss, s.kfgins, fo, truth_of(s), {});
}

void BM_Outage1h200Hz4Lengths(benchmark::State& state) {
  static const sim::SimResult s = drive("hg1700-typical", 3600.0);
  for (auto _ : state) {
    const assess::OutageRun run = outages(s, "");
    state.counters["outages"] = static_cast<double>(run.outages.size());
    state.counters["uncut_run_s"] = run.uncut_run_s;
    state.counters["outages_run_s"] = run.outages_run_s;
  }
}
BENCHMARK(BM_Outage1h200Hz4Lengths)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// --- Table 12 -------------------------------------------------------------------------------------

std::string cell(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

int write_table12(const std::string& path, double hours, const std::string& model) {
  const char* grades[3] = {"hg1700-typical", "hg1900-typical", "3dm-gx2-typical"};
  std::string rows;
  for (const char* g : grades) {
    const auto t0 = std::chrono::steady_clock::now();
    const sim::SimResult s = drive(g, hours * 3600.0);
    const assess::OutageRun run = outages(s, model);
    const auto summary = assess::summarise_outages(run);
    std::fprintf(stderr, "%s: %zu outages, %.0f s\n", g, run.outages.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    for (const auto& l : summary) {
      const auto& m = l.mean_abs_end;
      const auto& x = l.max_abs_end;
      rows += std::string("| ") + g + " | " + cell(l.length_s / 60.0, 0) + " | " + std::to_string(l.outages) + " | " +
              cell(m[0], 2) + " / " + cell(x[0], 2) + " | " + cell(m[1], 2) + " / " + cell(x[1], 2) + " | " + cell(m[2], 2) +
              " / " + cell(x[2], 2) + " | " + cell(std::max({m[3], m[4]}), 3) + " / " + cell(std::max({x[3], x[4]}), 3) + " | " +
              cell(m[6], 3) + " / " + cell(x[6], 3) + " | " + cell(m[7], 3) + " / " + cell(x[7], 3) + " | " + cell(m[8], 3) +
              " / " + cell(x[8], 3) + " | " + cell(l.rms_max_horizontal_m, 2) + " | " + cell(100 * l.inside_3sigma_pos, 0) +
              " % |\n";
    }
  }
  std::ofstream f(path + ".rows");
  f << "| IMU | outage [min] | n | E [m] | N [m] | D [m] | horiz. vel. [m/s] | roll [deg] | pitch [deg] | yaw [deg] | "
       "RMS max hor. [m] | in 3 sigma |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    << rows;
  std::fprintf(stderr, "rows written to %s.rows (mean / max of |drift at the outage end|)\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string table12, model;
  double hours = 1.0;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--table12=", 10) == 0) table12 = argv[i] + 10;
    if (std::strncmp(argv[i], "--hours=", 8) == 0) hours = std::atof(argv[i] + 8);
    if (std::strncmp(argv[i], "--model=", 8) == 0) model = argv[i] + 8;
  }
  if (!table12.empty()) return write_table12(table12, hours, model);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
