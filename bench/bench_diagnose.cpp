// Cost of `ldv diagnose` against one navigation run on a 30-min, 200 Hz tactical-grade drive with
// 1 Hz RTK and a hidden lever arm (so the diagnosis goes through screening, confirmation, rescreening).
//   build/bin/bench_diagnose
// Target (issue 6): the whole diagnosis under 10 times one `ldv nav` run. End to end from files:
//   ldv sim --grade hg1700-typical --duration 1800 --effect lever_arm --out /tmp/d30
//   time ldv nav --kfgins-config /tmp/d30/kfgins.yaml --out /tmp/d30/nav.nav
//   time ldv diagnose --kfgins-config /tmp/d30/kfgins.yaml --json /tmp/d30/diag.json
#include <benchmark/benchmark.h>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "toolbox/diagnose/diagnosis.hpp"

namespace {
using namespace ldv;

const sim::SimResult& drive() {
  static const sim::SimResult r = [] {
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.duration_s = 1800.0;
    req.scenario = "drive";
    req.effects = {"lever_arm"};
    return sim::simulate(req);
  }();
  return r;
}

void navigation_run(benchmark::State& state) {
  const auto& sim = drive();
  for (auto _ : state) {
    est::NavFilter filter(est::options_from_kfgins(sim.kfgins));
    est::run_navigation(sim.imu, sim.gnss, sim.kfgins, filter, {});
    benchmark::DoNotOptimize(filter.state().pos.lat_rad);
  }
}

void diagnosis(benchmark::State& state) {
  const auto& sim = drive();
  diag::DiagnoseInputs in;
  in.imu = sim.imu;
  in.gnss = sim.gnss;
  in.cfg = sim.kfgins;
  diag::DiagnoseOptions opt;
  opt.model = est::options_from_kfgins(sim.kfgins);
  int runs = 0;
  for (auto _ : state) {
    const diag::Diagnosis d = diag::diagnose(in, opt);
    runs = d.filter_runs;
    benchmark::DoNotOptimize(d.add.size());
  }
  state.counters["filter_runs"] = runs;
}

BENCHMARK(navigation_run)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(diagnosis)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
