// The paper's long-term study size: 16 h at 100 Hz on 6 axes (5.76 M samples each), overlapping
// ADEV, MDEV and HDEV (overlapping Hadamard) on log-spaced taus up to N/4, all channels in parallel.
// Target: < 3 s in total on the 2-core build machine.
#include <benchmark/benchmark.h>

#include <cmath>
#include <atomic>
#include <random>
#include <thread>

#include "toolbox/allan/analysis.hpp"
#include "toolbox/allan/deviation.hpp"
#include "toolbox/allan/phase_series.hpp"
#include "toolbox/allan/tau_list.hpp"

using namespace ldv::allan;

namespace {

constexpr double kRateHz = 100.0;
constexpr long kSamples = static_cast<long>(16 * 3600 * kRateHz);

const std::vector<PhaseSeries>& six_axes() {
  static const std::vector<PhaseSeries> axes = [] {
    std::vector<PhaseSeries> a;
    std::mt19937_64 rng(42);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int c = 0; c < 6; ++c) {
      std::vector<double> y(kSamples);
      double walk = 0.0;
      for (auto& v : y) {
        v = 1e-3 * g(rng) + walk + 0.01;  // white + random walk + bias
        walk += 1e-7 * g(rng);
      }
      a.push_back(phase_from_rates(std::move(y), 1.0 / kRateHz, "axis", "rad/s"));
    }
    return a;
  }();
  return axes;
}

// Every (axis, deviation) pair is one job; two workers (the machine's cores) take jobs in turn.
void run(const std::vector<Deviation>& devs, benchmark::State& state) {
  const auto& axes = six_axes();
  const std::vector<long> ms = averaging_factors(TauSpacing::kLog, default_max_factor(kSamples + 1), 10);
  for (auto _ : state) {
    std::vector<std::pair<int, Deviation>> jobs;
    for (int a = 0; a < 6; ++a)
      for (Deviation d : devs) jobs.emplace_back(a, d);
    std::atomic<size_t> next{0};
    std::atomic<double> checksum{0.0};
    auto worker = [&] {
      for (size_t j; (j = next++) < jobs.size();) {
        double s = 0;
        for (const auto& p : deviations(axes[jobs[j].first].x, axes[jobs[j].first].tau0_s, jobs[j].second, ms)) s += p.dev;
        checksum = checksum + s;
      }
    };
    std::thread t(worker);
    worker();
    t.join();
    benchmark::DoNotOptimize(checksum.load());
  }
  state.counters["taus"] = static_cast<double>(ms.size());
  state.counters["samples_per_axis"] = static_cast<double>(kSamples);
}

void BM_Oadev_Mdev_Ohdev_16h_100Hz_6axes(benchmark::State& s) { run({Deviation::kOadev, Deviation::kMdev, Deviation::kOhdev}, s); }
void BM_Oadev_16h_100Hz_6axes(benchmark::State& s) { run({Deviation::kOadev}, s); }
void BM_Mdev_16h_100Hz_6axes(benchmark::State& s) { run({Deviation::kMdev}, s); }
void BM_Hdev_16h_100Hz_6axes(benchmark::State& s) { run({Deviation::kHdev}, s); }
void BM_Ohdev_16h_100Hz_6axes(benchmark::State& s) { run({Deviation::kOhdev}, s); }

// The whole `ldv allan` analysis of one axis of the 16 h record (OADEV with intervals and the GM
// noise fit), the Allan-curve fit alone against the curve fit plus the likelihood refinement:
// what the refinement costs.
void analyse_one_axis(bool likelihood, benchmark::State& state) {
  const PhaseSeries& axis = six_axes().front();
  AnalysisOptions opt;
  opt.fit_options.gauss_markov = true;
  opt.fit_options.likelihood = likelihood;
  for (auto _ : state) {
    const auto r = analyze({axis}, opt).front();
    benchmark::DoNotOptimize(r.fit->model_avar(1.0));
  }
}
void BM_Analysis_CurveFit_16h_100Hz_1axis(benchmark::State& s) { analyse_one_axis(false, s); }
void BM_Analysis_CurveAndLikelihoodFit_16h_100Hz_1axis(benchmark::State& s) { analyse_one_axis(true, s); }

}  // namespace

BENCHMARK(BM_Analysis_CurveFit_16h_100Hz_1axis)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Analysis_CurveAndLikelihoodFit_16h_100Hz_1axis)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Oadev_Mdev_Ohdev_16h_100Hz_6axes)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();
BENCHMARK(BM_Oadev_16h_100Hz_6axes)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Mdev_16h_100Hz_6axes)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Hdev_16h_100Hz_6axes)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_Ohdev_16h_100Hz_6axes)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK_MAIN();
