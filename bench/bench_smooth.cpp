// The RTS smoother against the forward filter alone (issue 15: 1 h at 200 Hz smoothed in at most 3x the forward
// run's time), in process, on a 1 h, 200 Hz tactical-grade drive with 5 Hz RTK:
//   build/bin/bench_smooth
// Peak memory as users run it: /usr/bin/time -f '%e s %M KB' build/bin/ldv smooth --kfgins-config DIR/kfgins.yaml
// beside the same with `ldv nav` (reading and writing the files included).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/smooth/rts_recorder.hpp"
#include "sim/simulator.hpp"

namespace {
using namespace ldv;

const sim::SimResult& hour_drive() {
  static const sim::SimResult r = [] {
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.duration_s = 3600.0;
    req.gnss_rate_hz = 5.0;
    req.scenario = "drive";
    return sim::simulate(req);
  }();
  return r;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

// The forward filter, keeping every epoch's state as `ldv nav` writes it.
void forward(benchmark::State& state, const char* model) {
  const auto& sim = hour_drive();
  for (auto _ : state) {
    est::FilterOptions o = est::options_from_kfgins(sim.kfgins);
    o.model = model;
    est::NavFilter filter(o);
    std::vector<est::NavState> rows;
    rows.reserve(sim.imu.size());
    est::RunCallbacks cb;
    cb.on_epoch = [&](const est::NavFilter& f) { rows.push_back(f.state()); };
    est::run_navigation(sim.imu, sim.gnss, sim.kfgins, filter, cb);
    benchmark::DoNotOptimize(rows.back().pos.lat_rad);
  }
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

// Forward with the recorder, the backward pass, and every row smoothed.
void smoothed(benchmark::State& state, const char* model) {
  const auto& sim = hour_drive();
  for (auto _ : state) {
    est::FilterOptions o = est::options_from_kfgins(sim.kfgins);
    o.model = model;
    est::NavFilter filter(o);
    est::RtsRecorder recorder(filter);
    filter.set_observer(&recorder);
    est::RunCallbacks cb;
    cb.on_epoch = [&](const est::NavFilter& f) { recorder.add_row(f, 0); };
    est::run_navigation(sim.imu, sim.gnss, sim.kfgins, filter, cb);
    state.counters["records_on_disk_MB"] = recorder.bytes_on_disk() / 1e6;
    const est::SmoothedRun run = recorder.smooth();
    double lat = 0.0;
    for (std::size_t i = 0; i < run.size(); ++i) lat += run.row(i).smoothed.pos.lat_rad;
    benchmark::DoNotOptimize(lat);
  }
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

BENCHMARK_CAPTURE(forward, kfgins21, "kfgins21")->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(smoothed, kfgins21, "kfgins21")->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(forward, geoldv51, "geoldv51")->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(smoothed, geoldv51, "geoldv51")->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
