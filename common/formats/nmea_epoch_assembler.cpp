#include "common/formats/nmea_epoch_assembler.hpp"

#include <algorithm>
#include <cmath>

namespace ldv::gnss {
namespace {
GpsTime add_seconds(GpsTime t, double s) {
  t.sow_s += s;
  const double weeks = std::floor(t.sow_s / kSecondsPerWeek);
  t.week += static_cast<int>(weeks);
  t.sow_s -= weeks * kSecondsPerWeek;
  return t;
}

GpsTime gps_from_utc(const UtcDate& date, double utc_seconds_of_day, double gps_minus_utc_s) {
  // Midnight first, then add the time of day: keeps sub-microsecond resolution in sow_s.
  const GpsTime midnight = gps_from_calendar({date.year, date.month, date.day, 0, 0, 0.0});
  return add_seconds(midnight, utc_seconds_of_day + gps_minus_utc_s);
}

std::int64_t key_of(double seconds_of_day) { return std::llround(seconds_of_day * 1000.0); }
}  // namespace

std::optional<GnssQuality> quality_from_gga(int quality_code) {
  switch (quality_code) {
    case 1: return GnssQuality::kSingle;
    case 2: return GnssQuality::kDgps;
    case 3: return GnssQuality::kSingle;  // "PPS mode" (precise code, military): still a code solution
    case 4: return GnssQuality::kFixed;
    case 5: return GnssQuality::kFloat;
    default: return std::nullopt;
  }
}

NmeaEpochAssembler::NmeaEpochAssembler(SolutionHandler on_solution, LabelHandler on_label, NmeaEpochOptions options)
    : on_solution_(std::move(on_solution)), on_label_(std::move(on_label)), options_(options) {}

void NmeaEpochAssembler::enter_epoch(double utc_seconds_of_day) {
  const std::int64_t key = key_of(utc_seconds_of_day);
  if (key == epoch_.key_ms) return;
  if (epoch_.key_ms >= 0) {
    close_epoch();
    previous_parts_ = epoch_.parts;
  }
  epoch_ = Epoch{};
  epoch_.key_ms = key;
  epoch_.utc_seconds_of_day = utc_seconds_of_day;
}

void NmeaEpochAssembler::add_part(Part p) {
  epoch_.parts |= p;
  // Emit as soon as everything the receiver sent last epoch is here: no waiting for the next one.
  if ((epoch_.parts & kGga) && previous_parts_ != 0 && (epoch_.parts & previous_parts_) == previous_parts_) {
    close_epoch();
  }
}

void NmeaEpochAssembler::on_sentence(std::string_view sentence) {
  const auto address = nmea_address(sentence);
  if (!address) {
    ++counters_.malformed;
    return;
  }
  const std::string_view type = address->type;
  if (type == "GGA") {
    const auto gga = parse_gga(sentence);
    if (!gga) return void(++counters_.malformed);
    enter_epoch(gga->utc_seconds_of_day);
    epoch_.gga = gga;
    add_part(kGga);
  } else if (type == "GST") {
    const auto gst = parse_gst(sentence);
    if (!gst) return void(++counters_.malformed);
    enter_epoch(gst->utc_seconds_of_day);
    epoch_.gst = gst;
    add_part(kGst);
  } else if (type == "RMC") {
    const auto rmc = parse_rmc(sentence);
    if (!rmc) return void(++counters_.malformed);
    enter_epoch(rmc->utc_seconds_of_day);
    epoch_.date = rmc->date;
    if (rmc->valid && rmc->course_true_rad) {
      epoch_.speed_mps = rmc->speed_mps;
      epoch_.course_rad = rmc->course_true_rad;
    }
    if (rmc->valid) emit_label(rmc->date, rmc->utc_seconds_of_day);
    add_part(kRmc);
  } else if (type == "ZDA") {
    const auto zda = parse_zda(sentence);
    if (!zda) return void(++counters_.malformed);
    enter_epoch(zda->utc_seconds_of_day);
    epoch_.date = zda->date;
    emit_label(zda->date, zda->utc_seconds_of_day);
    add_part(kZda);
  } else if (type == "VTG") {
    // VTG has no time tag: it belongs to the epoch in progress.
    const auto vtg = parse_vtg(sentence);
    if (!vtg) return void(++counters_.malformed);
    if (epoch_.key_ms < 0) return;
    if (vtg->course_true_rad && vtg->mode != 'N') {
      epoch_.speed_mps = vtg->speed_mps;
      epoch_.course_rad = vtg->course_true_rad;
    }
    add_part(kVtg);
  } else {
    ++counters_.ignored;
  }
}

void NmeaEpochAssembler::emit_label(const UtcDate& date, double utc_seconds_of_day) {
  // Only a whole second names a pulse; sub-second epochs (4 Hz, 10 Hz) do not.
  if (std::abs(utc_seconds_of_day - std::round(utc_seconds_of_day)) > 1e-3) return;
  PpsTimeLabel label;
  label.pulse_time = gps_from_utc(date, std::round(utc_seconds_of_day), options_.gps_minus_utc_s);
  label.refers = PpsTimeLabel::Refers::kLastPulse;
  if (last_label_ && last_label_->week == label.pulse_time.week && last_label_->sow_s == label.pulse_time.sow_s) {
    return;  // RMC and ZDA of the same second
  }
  last_label_ = label.pulse_time;
  ++counters_.labels;
  if (on_label_) on_label_(label);
}

std::optional<GpsTime> NmeaEpochAssembler::gps_time_of(const Epoch& e) {
  if (e.date) {
    last_date_ = e.date;
    last_date_seconds_of_day_ = e.utc_seconds_of_day;
  }
  if (!last_date_) return std::nullopt;
  GpsTime t = gps_from_utc(*last_date_, e.utc_seconds_of_day, options_.gps_minus_utc_s);
  // A date from an earlier epoch and a time of day that went backwards: midnight passed.
  if (!e.date && e.utc_seconds_of_day + 43200.0 < last_date_seconds_of_day_) t = add_seconds(t, 86400.0);
  return t;
}

void NmeaEpochAssembler::close_epoch() {
  if (epoch_.emitted || epoch_.key_ms < 0) return;
  epoch_.emitted = true;
  const auto time = gps_time_of(epoch_);
  const auto quality = epoch_.gga && epoch_.gga->has_position ? quality_from_gga(epoch_.gga->quality_code)
                                                              : std::nullopt;
  if (!quality) return void(++counters_.epochs_without_fix);
  if (!time) return void(++counters_.epochs_without_date);

  const NmeaGga& gga = *epoch_.gga;
  GnssSolution s;
  s.time = *time;
  s.fix.t_s = time->sow_s;
  s.fix.pos = {gga.lat_rad, gga.lon_rad, gga.ellipsoid_height_m()};
  s.fix.quality = *quality;
  s.fix.num_sats = gga.num_sats;
  s.fix.age_s = gga.correction_age_s.value_or(0.0);
  s.fix.ratio = 0.0;  // NMEA does not carry the AR ratio
  s.pos_cov_ned_m2.setZero();
  if (epoch_.gst) {
    const NmeaGst& g = *epoch_.gst;
    s.pos_cov_ned_m2(0, 0) = g.lat_std_m * g.lat_std_m;
    s.pos_cov_ned_m2(1, 1) = g.lon_std_m * g.lon_std_m;
    s.pos_cov_ned_m2(2, 2) = g.alt_std_m * g.alt_std_m;
    // The error ellipse gives the north-east correlation the per-axis stds cannot.
    if (g.semi_major_std_m > 0.0 && g.lat_std_m > 0.0 && g.lon_std_m > 0.0) {
      const double c = std::cos(g.semi_major_orientation_rad), sn = std::sin(g.semi_major_orientation_rad);
      const double a2 = g.semi_major_std_m * g.semi_major_std_m, b2 = g.semi_minor_std_m * g.semi_minor_std_m;
      const double max_ne = 0.999 * g.lat_std_m * g.lon_std_m;
      const double ne = std::clamp((a2 - b2) * c * sn, -max_ne, max_ne);
      s.pos_cov_ned_m2(0, 1) = s.pos_cov_ned_m2(1, 0) = ne;
    }
  } else {
    const double std_m = options_.default_std_m[static_cast<int>(*quality) - 1];
    s.pos_cov_ned_m2.diagonal().setConstant(std_m * std_m);
  }
  sync_std_from_cov(s);
  if (epoch_.speed_mps && epoch_.course_rad) {
    s.fix.has_velocity = true;
    s.fix.vel_n_mps = {*epoch_.speed_mps * std::cos(*epoch_.course_rad),
                       *epoch_.speed_mps * std::sin(*epoch_.course_rad), 0.0};
    s.fix.vel_std_n_mps = {options_.horizontal_velocity_std_mps, options_.horizontal_velocity_std_mps,
                           options_.vertical_velocity_std_mps};
  }
  ++counters_.solutions;
  if (on_solution_) on_solution_(s);
}

void NmeaEpochAssembler::flush() { close_epoch(); }

}  // namespace ldv::gnss
