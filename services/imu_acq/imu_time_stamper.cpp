#include "services/imu_acq/imu_time_stamper.hpp"

#include "services/imu_acq/timing/counter_unwrap.hpp"

namespace ldv::imu {

ImuTimeStamper::ImuTimeStamper(StamperOptions options, EdgeHandler on_edge)
    : options_(options),
      on_edge_(std::move(on_edge)),
      fit_(options.fit),
      matcher_([this](std::uint64_t c, std::optional<std::int64_t> s) { on_matched_edge(c, s); }, options.matcher) {}

std::int64_t ImuTimeStamper::extend(std::uint64_t raw_counter) {
  // Samples and latches come many times per wrap, so the nearest extension is the right one.
  const std::int64_t e = last_extended_ ? timing::unwrap_nearest(raw_counter, *last_extended_, options_.fit.counter_bits)
                                        : static_cast<std::int64_t>(raw_counter);
  last_extended_ = e;
  return e;
}

void ImuTimeStamper::on_pps_latch(std::uint64_t raw_counter, double host_time_s) {
  latch_host_time_s_ = host_time_s;
  matcher_.on_edge(raw_counter, host_time_s);
}

void ImuTimeStamper::on_label(const gnss::PpsTimeLabel& label, double host_time_s) {
  matcher_.on_label(label, host_time_s);
}

void ImuTimeStamper::poll(double host_time_s) { matcher_.poll(host_time_s); }

void ImuTimeStamper::on_matched_edge(std::uint64_t raw_counter, std::optional<std::int64_t> gps_second) {
  JudgedEdge e;
  e.counter = extend(raw_counter);
  e.host_time_s = latch_host_time_s_;
  e.result = fit_.add_pps_edge(raw_counter, gps_second);
  const bool known = e.result.verdict != timing::PpsEdgeVerdict::kUnlabelled;
  if (known) e.gps_second = e.result.gps_second;
  if (on_edge_) on_edge_(e);
}

Stamp ImuTimeStamper::stamp(std::uint64_t raw_counter, double host_time_s) {
  Stamp s;
  s.counter = extend(raw_counter);
  if (const auto t = fit_.stamp(raw_counter)) {
    s.time = *t;
    anchor_ = {s.counter, t->total_seconds()};
    return s;
  }
  // Unlocked: carry on from the last fitted stamp at the nominal rate (drift of tens of ppm over
  // the outage), or start from the host clock (milliseconds off, but in the right second).
  if (!anchor_) anchor_ = {s.counter, host_time_s - kGpsEpochInUnixSeconds + options_.gps_minus_utc_s};
  const double t_s = anchor_->second + static_cast<double>(s.counter - anchor_->first) / options_.fit.nominal_counter_hz;
  s.time = GpsTime::from_total_seconds(t_s);
  s.extrapolated = true;
  return s;
}

}  // namespace ldv::imu
