#include "common/formats/tagged_imu_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "common/formats/rtklib_time_tag.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {
namespace {
struct RawSample {
  double counter_s;
  double reception_gps_s;
  Vec3 f_b_mps2;
  Vec3 w_b_rad_s;
};

// Fits reception = offset + rate * counter to the lower envelope: the earliest arrival in each
// window is the one with the least transport delay.
void fit_lower_envelope(const std::vector<RawSample>& s, double& offset, double& rate) {
  constexpr double kWindow_s = 5.0;
  std::vector<std::pair<double, double>> env;  // (counter, reception)
  size_t i = 0;
  while (i < s.size()) {
    const double w0 = s[i].counter_s;
    size_t best = i;
    for (; i < s.size() && s[i].counter_s < w0 + kWindow_s; ++i)
      if (s[i].reception_gps_s - s[i].counter_s < s[best].reception_gps_s - s[best].counter_s) best = i;
    env.emplace_back(s[best].counter_s, s[best].reception_gps_s);
  }
  rate = 1.0;
  if (env.size() >= 2) {
    double mc = 0, mr = 0;
    for (auto& [c, r] : env) mc += c, mr += r;
    mc /= env.size();
    mr /= env.size();
    double scc = 0, scr = 0;
    for (auto& [c, r] : env) scc += (c - mc) * (c - mc), scr += (c - mc) * (r - mr);
    if (scc > 0) rate = scr / scc;
  }
  offset = s.front().reception_gps_s - rate * s.front().counter_s;
  for (const auto& x : s) offset = std::min(offset, x.reception_gps_s - rate * x.counter_s);
}
}  // namespace

std::vector<ImuIncrement> read_tagged_imu_csv(const std::string& csv_path, const std::string& tag_path,
                                              const TaggedImuCsvOptions& opt, TaggedImuCsvReport* report) {
  const RtklibTimeTag tag = read_rtklib_time_tag(tag_path);
  std::ifstream in(csv_path, std::ios::binary);
  if (!in) throw InputError(csv_path, 0, "cannot open IMU CSV file");
  TaggedImuCsvReport rep;
  std::vector<RawSample> raw;
  std::string line;
  std::vector<std::string_view> fields;
  long line_no = 0;
  uint64_t pos = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const uint64_t end_pos = pos + line.size();  // the line is complete once its last byte arrived
    pos = end_pos + 1;
    split_fields(line, fields);
    if (fields.empty()) continue;
    if (fields.size() != 7) {
      ++rep.skipped_lines;
      continue;
    }
    double v[7];
    try {
      for (int c = 0; c < 7; ++c) v[c] = parse_double(fields[c], csv_path, line_no, c + 1);
    } catch (const InputError&) {
      if (line_no == 1) throw;  // a header or wrong file, not a cut line
      ++rep.skipped_lines;
      continue;
    }
    RawSample s{v[6] * opt.counter_to_s, tag.reception_gps_s(end_pos),
                Vec3(v[0], v[1], v[2]) * opt.accel_to_mps2, Vec3(v[3], v[4], v[5]) * opt.gyro_to_rad_s};
    if (!raw.empty() && s.counter_s <= raw.back().counter_s) {
      ++rep.skipped_counter;
      continue;
    }
    raw.push_back(s);
  }
  if (raw.size() < 3) throw InputError(csv_path, 0, "fewer than 3 complete IMU samples (expected ax,ay,az,gx,gy,gz,t_ms)");

  double offset = 0, rate = 1;
  fit_lower_envelope(raw, offset, rate);
  rep.host_rate_error_ppm = (rate - 1.0) * 1e6;
  rep.rate_source = "host reception times (lower envelope)";
  const bool given = opt.counter_rate > 0.0;
  // A counter off by more than a crystal can be means the reception times are distorted (buffered or burst
  // delivery), not the counter: keep the counter's nominal rate.
  const bool implausible = !given && std::abs(rep.host_rate_error_ppm) > opt.max_host_rate_error_ppm;
  if (given || implausible) {
    rate = given ? opt.counter_rate : 1.0;
    rep.rate_source = given ? "given" : "device counter (host reception rate implausible)";
    // Offset from the earliest samples: the log's start is the one moment the reception is known to be prompt.
    offset = raw.front().reception_gps_s - rate * raw.front().counter_s;
    for (const auto& x : raw) {
      if (x.counter_s > raw.front().counter_s + opt.offset_window_s) break;
      offset = std::min(offset, x.reception_gps_s - rate * x.counter_s);
    }
  }
  rep.counter_rate = rate;
  std::vector<double> latency;
  latency.reserve(raw.size());
  for (const auto& s : raw) latency.push_back(s.reception_gps_s - (offset + rate * s.counter_s));
  std::sort(latency.begin(), latency.end());
  rep.min_latency_s = latency.front();
  rep.median_latency_s = latency[latency.size() / 2];
  rep.p99_latency_s = latency[static_cast<size_t>(0.99 * (latency.size() - 1))];

  std::vector<ImuIncrement> out;
  out.reserve(raw.size() - 1);
  for (size_t k = 1; k < raw.size(); ++k) {
    const double t0 = offset + rate * raw[k - 1].counter_s, t1 = offset + rate * raw[k].counter_s;
    ImuIncrement inc;
    inc.t_s = GpsTime::from_total_seconds(t1).sow_s;
    inc.dt_s = t1 - t0;
    inc.dtheta_b_rad = 0.5 * (raw[k - 1].w_b_rad_s + raw[k].w_b_rad_s) * inc.dt_s;
    inc.dvel_b_mps = 0.5 * (raw[k - 1].f_b_mps2 + raw[k].f_b_mps2) * inc.dt_s;
    out.push_back(inc);
  }
  rep.samples = static_cast<long>(raw.size());
  if (report) *report = rep;
  return out;
}

}  // namespace ldv
