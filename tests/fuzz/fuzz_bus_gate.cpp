// fusion's bus-input gate and engine under hostile but well-formed message streams (hostile_stream.hpp): NAV stays
// finite and plausible, its times only go forward, and after the clean last 2 s it has reached the stream's end.
#include "tests/fuzz/fuzz_support.hpp"
#include "tests/fuzz/hostile_stream.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::StreamOutcome r = fuzz::replay_hostile_stream(fuzz::hostile_stream(data, size));
  fuzz::require(r.finite_and_plausible, "a NAV output not finite or not plausible: " + r.first_bad);
  fuzz::require(r.times_increase, "NAV times went back");
  fuzz::require(r.nav > 0 && r.last_nav_t_s > r.last_imu_t_s - 0.5, "NAV stopped before the stream's end");
  return 0;
}
