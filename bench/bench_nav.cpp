// Throughput of the estimator (IMU samples per second) on a 900 s, 200 Hz tactical-grade drive with
// 5 Hz RTK (the KF-GINS reference file size: KF-GINS takes 3.2 s end to end on this machine).
//   build/bin/bench_nav            (filter only, and end to end: read files, filter, write .nav at 200 Hz)
// End to end as users run it: `time build/bin/ldv nav --kfgins-config DIR/kfgins.yaml --model kfgins21`.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "common/formats/kfgins_files.hpp"
#include "estimator/calibrate/imu_latency.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"

namespace {
using namespace ldv;

sim::SimResult& drive() {
  static sim::SimResult r = [] {
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.duration_s = 900.0;
    req.gnss_rate_hz = 5.0;
    req.scenario = "drive";
    sim::SimResult res = sim::simulate(req);
    const std::string dir = (std::filesystem::temp_directory_path() / "ldv_bench_nav").string();
    sim::write_outputs(res, dir);
    return res;
  }();
  return r;
}

void filter_only(benchmark::State& state, const char* model) {
  const auto& sim = drive();
  for (auto _ : state) {
    est::FilterOptions o = est::options_from_kfgins(sim.kfgins);
    o.model = model;
    est::NavFilter filter(o);
    est::run_navigation(sim.imu, sim.gnss, sim.kfgins, filter, {});
    benchmark::DoNotOptimize(filter.state().pos.lat_rad);
  }
  state.counters["imu_samples_per_s"] = benchmark::Counter(static_cast<double>(sim.imu.size()) * state.iterations(),
                                                           benchmark::Counter::kIsRate);
}

// The IMU-latency search `ldv nav` runs before the filter (issue 12) on the same drive: the whole file's turns
// against the GNSS track, 2 x (51 + 13 + 41) lags.
void imu_latency_search(benchmark::State& state) {
  const auto& sim = drive();
  for (auto _ : state) benchmark::DoNotOptimize(est::estimate_imu_latency(sim.imu, sim.gnss).lag_s);
}

// The land-vehicle aids at 200 Hz (issue 16: with NHC within 1.5x of the run without aids).
void filter_with_aids(benchmark::State& state, std::vector<std::string> aids) {
  const auto& sim = drive();
  for (auto _ : state) {
    est::FilterOptions o = est::options_from_kfgins(sim.kfgins);
    o.model = "kfgins21";
    o.aids.enabled = aids;
    est::NavFilter filter(o);
    est::run_navigation(sim.imu, sim.gnss, sim.kfgins, filter, {});
    benchmark::DoNotOptimize(filter.state().pos.lat_rad);
  }
  state.counters["imu_samples_per_s"] = benchmark::Counter(static_cast<double>(sim.imu.size()) * state.iterations(),
                                                           benchmark::Counter::kIsRate);
}

void end_to_end(benchmark::State& state, const char* model) {
  const auto& sim = drive();
  const KfGinsConfig cfg = load_kfgins_config(sim.kfgins.config_path.empty()
                                                  ? (std::filesystem::temp_directory_path() / "ldv_bench_nav/kfgins.yaml").string()
                                                  : sim.kfgins.config_path);
  const std::string out = (std::filesystem::temp_directory_path() / "ldv_bench_nav/bench.nav").string();
  for (auto _ : state) {
    const auto imu = read_kfgins_imu(cfg.imu_path);
    const auto gnss = read_kfgins_gnss(cfg.gnss_path);
    est::FilterOptions o = est::options_from_kfgins(cfg);
    o.model = model;
    est::NavFilter filter(o);
    NavWriter writer(out);
    est::RunCallbacks cb;
    NavRecord rec;
    cb.on_epoch = [&](const est::NavFilter& f) {
      rec.sow_s = f.state().t_s;
      rec.pos = f.state().pos;
      rec.vel_n_mps = f.state().v_n_mps;
      rec.rpy_rad = f.state().rpy_rad();
      writer.write(rec);
    };
    est::run_navigation(imu, gnss, cfg, filter, cb);
  }
  state.counters["imu_samples_per_s"] = benchmark::Counter(static_cast<double>(sim.imu.size()) * state.iterations(),
                                                           benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(filter_only, ins15, "ins15")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(filter_only, kfgins21, "kfgins21")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(filter_only, geoldv51, "geoldv51")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(imu_latency_search)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(filter_with_aids, kfgins21_nhc, std::vector<std::string>{"nhc"})->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(filter_with_aids, kfgins21_nhc_zaru, std::vector<std::string>{"nhc", "zaru"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(end_to_end, kfgins21, "kfgins21")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(end_to_end, geoldv51, "geoldv51")->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
