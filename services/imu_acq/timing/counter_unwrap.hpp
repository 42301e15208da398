#pragma once
// Free-running hardware counters wrap (a 32-bit counter at 10 MHz every 429.5 s). These helpers
// extend a raw reading to 64 bits relative to a nearby, already extended reading.
#include <cstdint>

namespace ldv::timing {

// Extends `raw` (the low `bits` bits of a counter) to the value nearest `reference` (an extended
// reading). Correct while the two are less than half a wrap apart.
inline std::int64_t unwrap_nearest(std::uint64_t raw, std::int64_t reference, int bits) {
  if (bits >= 64) return static_cast<std::int64_t>(raw);
  const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
  const std::uint64_t diff = (raw - static_cast<std::uint64_t>(reference)) & mask;
  const std::int64_t half = std::int64_t{1} << (bits - 1);
  const std::int64_t signed_diff = static_cast<std::int64_t>(diff) >= half
                                       ? static_cast<std::int64_t>(diff) - (half << 1)
                                       : static_cast<std::int64_t>(diff);
  return reference + signed_diff;
}

// Extends `raw` given the expected number of ticks since `reference` (e.g. from the GPS seconds
// elapsed): resolves any number of wraps, for gaps longer than half a wrap.
inline std::int64_t unwrap_expected(std::uint64_t raw, std::int64_t reference, double expected_ticks, int bits) {
  if (bits >= 64) return static_cast<std::int64_t>(raw);
  const std::int64_t wrap = std::int64_t{1} << bits;
  const std::uint64_t mask = static_cast<std::uint64_t>(wrap) - 1;
  const auto forward = static_cast<std::int64_t>((raw - static_cast<std::uint64_t>(reference)) & mask);
  const double wraps = (expected_ticks - static_cast<double>(forward)) / static_cast<double>(wrap);
  const auto k = static_cast<std::int64_t>(wraps + (wraps >= 0 ? 0.5 : -0.5));
  return reference + forward + k * wrap;
}

}  // namespace ldv::timing
