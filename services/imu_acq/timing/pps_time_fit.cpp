#include "services/imu_acq/timing/pps_time_fit.hpp"

#include <algorithm>
#include <cmath>

#include "services/imu_acq/timing/counter_unwrap.hpp"

namespace ldv::timing {
namespace {
constexpr std::int64_t kSecondsPerWeekInt = 604800;
}

PpsTimeFit::PpsTimeFit(PpsTimeFitOptions options)
    : options_(options), seconds_per_tick_(1.0 / options.nominal_counter_hz) {}

double PpsTimeFit::seconds_since_newest(std::int64_t counter) const {
  return offset_s_ + seconds_per_tick_ * static_cast<double>(counter - window_.back().counter);
}

void PpsTimeFit::restart(const Edge& e) {
  window_.clear();
  accepted_since_restart_ = 0;
  locked_ = false;
  disagreements_ = 0;
  // Keep the frequency learnt so far: a restart is about the labels, not the oscillator.
  accept(e);
}

void PpsTimeFit::accept(const Edge& e) {
  late_since_accept_ = 0;
  window_.push_back(e);
  while (window_.size() > options_.window_edges) window_.pop_front();
  ++accepted_since_restart_;
  ++counters_.accepted;
  locked_ = accepted_since_restart_ >= options_.edges_to_lock;
  refit();
}

void PpsTimeFit::refit() {
  const Edge& ref = window_.back();
  offset_s_ = 0.0;
  residual_rms_s_ = 0.0;
  if (window_.size() < 2) return;
  // Least squares t = a + b x about the newest edge (small numbers, no cancellation).
  double sx = 0, sy = 0;
  for (const Edge& e : window_) {
    sx += static_cast<double>(e.counter - ref.counter);
    sy += static_cast<double>(e.second - ref.second);
  }
  const double n = static_cast<double>(window_.size());
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (const Edge& e : window_) {
    const double dx = static_cast<double>(e.counter - ref.counter) - mx;
    const double dy = static_cast<double>(e.second - ref.second) - my;
    sxx += dx * dx;
    sxy += dx * dy;
  }
  if (sxx <= 0.0) return;
  seconds_per_tick_ = sxy / sxx;
  offset_s_ = my - seconds_per_tick_ * mx;
  double ss = 0;
  for (const Edge& e : window_) {
    const double r = seconds_since_newest(e.counter) - static_cast<double>(e.second - ref.second);
    ss += r * r;
  }
  residual_rms_s_ = std::sqrt(ss / n);
}

PpsEdgeResult PpsTimeFit::add_pps_edge(std::uint64_t raw_counter, std::optional<std::int64_t> label) {
  ++counters_.edges;
  PpsEdgeResult result;
  const int bits = options_.counter_bits;
  if (window_.empty()) {
    if (!label) {
      ++counters_.unlabelled;
      return result;
    }
    restart({unwrap_nearest(raw_counter, 0, bits), *label});
    result.verdict = PpsEdgeVerdict::kAccepted;
    result.gps_second = *label;
    return result;
  }

  const Edge newest = window_.back();
  // A label saying the gap exceeds a quarter wrap resolves the wraps; otherwise take the nearest.
  const double wrap_s = bits >= 64 ? INFINITY : std::ldexp(seconds_per_tick_, bits);
  const bool long_gap = label && std::abs(static_cast<double>(*label - newest.second)) > wrap_s / 4;
  const std::int64_t counter =
      long_gap ? unwrap_expected(raw_counter, newest.counter,
                                 static_cast<double>(*label - newest.second) / seconds_per_tick_, bits)
               : unwrap_nearest(raw_counter, newest.counter, bits);
  const double dt = seconds_since_newest(counter);
  const std::int64_t whole = std::llround(dt);
  const std::int64_t second = newest.second + whole;
  result.gps_second = second;
  result.residual_s = dt - static_cast<double>(whole);

  const double tolerance_ppm =
      locked_ ? options_.locked_frequency_tolerance_ppm : options_.acquisition_frequency_tolerance_ppm;
  const double tolerance_s = options_.edge_tolerance_s + std::abs(dt) * tolerance_ppm * 1e-6;
  const bool timing_bad = std::abs(result.residual_s) > tolerance_s || whole <= 0;
  const bool label_bad = label && *label != second;

  auto reacquire = [&] {
    ++counters_.reacquisitions;
    restart({counter, *label});
    result.verdict = PpsEdgeVerdict::kReacquired;
    result.gps_second = *label;
    result.residual_s = 0.0;
    return result;
  };

  // Before lock nothing is trusted yet: any inconsistency restarts on the newest labelled edge.
  if (!locked_ && label && (timing_bad || label_bad)) return reacquire();

  if (timing_bad) {
    ++disagreements_;
    if (label && disagreements_ >= options_.disagreements_to_reacquire) return reacquire();
    if (whole > 0 && result.residual_s > 0) {
      ++counters_.late;
      ++late_since_accept_;
      result.verdict = PpsEdgeVerdict::kLate;
    } else {
      // Before its second (a glitch, or a pulse more than half a second late) or a repeat.
      ++counters_.spurious;
      result.verdict = PpsEdgeVerdict::kSpurious;
    }
    return result;
  }

  result.verdict = PpsEdgeVerdict::kAccepted;
  if (label_bad) {
    ++counters_.wrong_labels;
    ++disagreements_;
    if (disagreements_ >= options_.disagreements_to_reacquire) return reacquire();
    result.verdict = PpsEdgeVerdict::kAcceptedWrongLabel;
  } else if (label) {
    disagreements_ = 0;
  }
  if (!label) ++counters_.unlabelled;
  // Seconds skipped, less those whose pulse came but late: those were not missing.
  result.missing_before = std::max<std::int64_t>(0, whole - 1 - late_since_accept_);
  counters_.missing += static_cast<std::uint64_t>(result.missing_before);
  accept({counter, second});
  return result;
}

std::optional<GpsTime> PpsTimeFit::stamp(std::uint64_t raw_counter) const {
  if (!locked_) return std::nullopt;
  const Edge& newest = window_.back();
  const double dt = seconds_since_newest(unwrap_nearest(raw_counter, newest.counter, options_.counter_bits));
  // Whole seconds in integers, the fraction in double: sub-nanosecond resolution at any week.
  const double whole = std::floor(dt);
  const std::int64_t second = newest.second + static_cast<std::int64_t>(whole);
  std::int64_t week = second / kSecondsPerWeekInt;
  if (second < 0 && second % kSecondsPerWeekInt != 0) --week;
  return GpsTime{static_cast<int>(week),
                 static_cast<double>(second - week * kSecondsPerWeekInt) + (dt - whole)};
}

}  // namespace ldv::timing
