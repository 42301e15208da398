#include "sim/device_streams.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/formats/imu_device_frame.hpp"
#include "common/formats/nmea_writer.hpp"
#include "sim/random.hpp"

namespace ldv::sim {
namespace {
int nmea_quality(GnssQuality q) {
  switch (q) {
    case GnssQuality::kFixed: return 4;
    case GnssQuality::kFloat: return 5;
    case GnssQuality::kDgps: return 2;
    case GnssQuality::kSbas: return 2;
    default: return 1;
  }
}
char rmc_mode(GnssQuality q) {
  switch (q) {
    case GnssQuality::kFixed: return 'R';
    case GnssQuality::kFloat: return 'F';
    case GnssQuality::kDgps: case GnssQuality::kSbas: return 'D';
    default: return 'A';
  }
}
}  // namespace

DeviceStreams make_device_streams(const std::vector<ImuIncrement>& imu, double t0_sow, int week,
                                  const std::vector<GnssFix>& gnss, const std::vector<double>& latency,
                                  double gnss_rate_hz, double latency_mean_s, int leap_seconds, const Oscillator& osc,
                                  uint64_t seed, bool with_noise) {
  DeviceStreams out;
  Rng jitter(seed, "oscillator_jitter");
  const double f = osc.nominal_hz * (1.0 + osc.ppm * 1e-6);
  auto counter_at = [&](double t_sow) {
    const double j = with_noise ? osc.latch_jitter_s * jitter.normal() : 0.0;
    const double counts = osc.phase_counts + f * (t_sow - t0_sow + j);
    return static_cast<uint32_t>(static_cast<uint64_t>(std::floor(counts)) & 0xFFFFFFFFull);
  };
  struct Event {
    double t;
    int stream;
    std::string nmea;  // stream 1
    size_t imu_index;  // stream 0, or SIZE_MAX for a PPS
  };
  std::vector<Event> events;
  events.reserve(imu.size() + imu.size() / 50 + gnss.size() * 4);
  for (size_t k = 0; k < imu.size(); ++k) events.push_back({imu[k].t_s, 0, {}, k});
  const double t_end = imu.empty() ? t0_sow : imu.back().t_s;
  for (double s = std::ceil(t0_sow); s <= t_end; s += 1.0) events.push_back({s, 0, {}, SIZE_MAX});

  // NMEA: every epoch of the GNSS grid; quality 0 when there is no fix (outage).
  std::map<long, size_t> fix_at;  // epoch index -> fix
  for (size_t i = 0; i < gnss.size(); ++i) fix_at[std::lround(gnss[i].t_s * gnss_rate_hz)] = i;
  const long first = static_cast<long>(std::ceil(t0_sow * gnss_rate_hz - 1e-9));
  const long last = static_cast<long>(std::floor(t_end * gnss_rate_hz + 1e-9));
  for (long j = first; j <= last; ++j) {
    const double t = static_cast<double>(j) / gnss_rate_hz;
    const CalendarTime utc = nmea::utc_from_gps(GpsTime{week, t}, leap_seconds);
    const auto it = fix_at.find(j);
    std::string text;
    double arrival = t + latency_mean_s;
    if (it != fix_at.end()) {
      const GnssFix& g = gnss[it->second];
      arrival = t + latency[it->second];
      nmea::GgaFields ff;
      ff.quality = nmea_quality(g.quality);
      ff.num_sats = g.num_sats;
      ff.age_s = g.quality == GnssQuality::kSingle ? -1.0 : g.age_s;
      text = nmea::gga(utc, g.pos, ff) + nmea::gst(utc, g.pos_std_ned_m.x(), g.pos_std_ned_m.y(), g.pos_std_ned_m.z()) +
             nmea::rmc(utc, g.pos, g.vel_n_mps.x(), g.vel_n_mps.y(), rmc_mode(g.quality));
    } else {
      char body[64];
      std::snprintf(body, sizeof body, "GNGGA,%02d%02d%05.2f,,,,,0,00,99.9,,M,,M,,", utc.hour, utc.minute, utc.second);
      text = nmea::sentence(body);
    }
    if (std::abs(t - std::round(t)) < 1e-9) text += nmea::zda(utc);  // labels this second's PPS
    events.push_back({arrival, 1, std::move(text), 0});
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });

  imu_device::IncrementQuantizer quant;
  uint16_t imu_seq = 0, pps_seq = 0;
  for (const Event& e : events) {
    if (e.stream == 0) {
      const size_t before = out.imu_bytes.size();
      if (e.imu_index == SIZE_MAX) {
        imu_device::append_frame(out.imu_bytes, imu_device::PpsLatchFrame{counter_at(e.t), pps_seq++});
      } else {
        const ImuIncrement& s = imu[e.imu_index];
        imu_device::ImuSampleFrame fr;
        fr.counter = counter_at(e.t);
        fr.sequence = imu_seq++;
        bool over = false;
        fr.dtheta_lsb = quant.dtheta(s.dtheta_b_rad.data(), over);
        fr.dvel_lsb = quant.dvel(s.dvel_b_mps.data(), over);
        fr.status = over ? imu_device::kStatusOverRange : 0;
        imu_device::append_frame(out.imu_bytes, fr);
      }
      out.schedule.push_back({e.t, 0, before, out.imu_bytes.size() - before});
    } else {
      out.schedule.push_back({e.t, 1, out.nmea_text.size(), e.nmea.size()});
      out.nmea_text += e.nmea;
    }
  }
  return out;
}

}  // namespace ldv::sim
