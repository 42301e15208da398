// Simulator speed: 1 h at 200 Hz on the default drive with every effect injected and a noisy grade
// (target: under 10 s). Also the cost of writing all outputs and of the truth integration alone.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "sim/effects.hpp"
#include "sim/simulator.hpp"

namespace {
ldv::sim::SimRequest hour_with_all_effects() {
  ldv::sim::SimRequest r;
  r.grade = "hg1700-typical";
  r.scenario = "drive";
  r.duration_s = 3600.0;
  r.imu_rate_hz = 200.0;
  r.gnss_rate_hz = 10.0;
  r.gnss_velocity = true;
  for (const auto& e : ldv::sim::effect_table()) r.effects.push_back(e.name);
  r.outages = {{600.0, 60.0}, {1800.0, 120.0}};
  return r;
}

void BM_Simulate1h200HzAllEffects(benchmark::State& state) {
  const auto req = hour_with_all_effects();
  for (auto _ : state) {
    auto r = ldv::sim::simulate(req);
    benchmark::DoNotOptimize(r.imu.data());
  }
}
BENCHMARK(BM_Simulate1h200HzAllEffects)->Unit(benchmark::kSecond)->Iterations(1);

void BM_Simulate1h200HzPerfect(benchmark::State& state) {
  ldv::sim::SimRequest req;
  req.scenario = "drive";
  req.duration_s = 3600.0;
  for (auto _ : state) {
    auto r = ldv::sim::simulate(req);
    benchmark::DoNotOptimize(r.imu.data());
  }
}
BENCHMARK(BM_Simulate1h200HzPerfect)->Unit(benchmark::kSecond)->Iterations(1);

void BM_SimulateAndWrite1h200HzAllEffects(benchmark::State& state) {
  const auto req = hour_with_all_effects();
  const auto dir = std::filesystem::temp_directory_path() / "ldv_bench_sim";
  for (auto _ : state) {
    auto r = ldv::sim::simulate(req);
    ldv::sim::write_outputs(r, dir.string());
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_SimulateAndWrite1h200HzAllEffects)->Unit(benchmark::kSecond)->Iterations(1);
}  // namespace

BENCHMARK_MAIN();
