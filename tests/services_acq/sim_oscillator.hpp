#pragma once
// A time-stamp unit's free-running counter for tests: nominal_hz off by ppm, latched with jitter,
// 32-bit wrap. counter(t) for GPS time t [total seconds since t0].
#include <cmath>
#include <cstdint>
#include <random>

namespace ldv::test {

struct SimOscillator {
  double nominal_hz = 10e6;
  double ppm = 50.0;
  double phase_counts = 123456789.0;
  double latch_jitter_s = 20e-9;
  std::mt19937_64 rng{7};

  std::uint32_t latch(double t_since_t0_s) {
    std::normal_distribution<double> jitter(0.0, latch_jitter_s);
    const double counts = phase_counts + nominal_hz * (1.0 + ppm * 1e-6) * (t_since_t0_s + jitter(rng));
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::floor(counts)) & 0xFFFFFFFFull);
  }
};

}  // namespace ldv::test
