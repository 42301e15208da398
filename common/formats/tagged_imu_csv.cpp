#include "common/formats/tagged_imu_csv.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdint>

#include "common/formats/imu_time_gaps.hpp"
#include "common/formats/rtklib_time_tag.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"
#include "common/io/text_table.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {
namespace {
struct RawSample {
  double counter_s;  // since the first kept sample (relative: an absolute 64-bit counter does not fit a double)
  uint64_t counter;  // unwrapped ticks
  unsigned long long end_offset;  // stored-file offset of the line's '\n' (the line is complete once it arrived)
  long line;
  long long crs_through;  // CRs the stored file lacks up to and including this line's end (LF-only lines)
  Vec3 f_b_mps2;
  Vec3 w_b_rad_s;
  double reception_gps_s = 0.0;
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
    // Every window takes at least its first sample, so the loop ends whatever the counter values.
    for (++i; i < s.size() && s[i].counter_s < w0 + kWindow_s; ++i)
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

bool parse_counter(std::string_view f, uint64_t& out, bool& too_large) {
  const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), out);
  too_large = ec == std::errc::result_out_of_range;
  return ec == std::errc() && ptr == f.data() + f.size();
}

// The tag file counts bytes as the host received them. The CSV as stored may have lost a CR per line (git
// normalises CRLF to LF): its last position then lies beyond the stored size, within the size with CRs. The
// convention whose size is at least the last tagged position, and closest to it, is the one the tags count.
bool tags_count_crlf(const RtklibTimeTag& tag, unsigned long long stored_size, long long missing_crs,
                     const std::string& csv_path, const std::string& tag_path) {
  const unsigned long long last = tag.entries.back().file_pos;
  const unsigned long long crlf_size = stored_size + static_cast<unsigned long long>(missing_crs);
  if (last <= stored_size) return false;
  if (missing_crs > 0 && last <= crlf_size) return true;
  throw InputError(tag_path, 0,
                   "the last tagged byte position " + std::to_string(last) + " lies beyond " + csv_path + " (" +
                       std::to_string(stored_size) + " bytes as stored, " + std::to_string(crlf_size) +
                       " with CRLF line ends): expected the tag file of this CSV");
}
}  // namespace

std::vector<ImuIncrement> read_tagged_imu_csv(const std::string& csv_path, const std::string& tag_path,
                                              const TaggedImuCsvOptions& opt, TaggedImuCsvReport* report) {
  if (opt.counter_bits != 0 && (opt.counter_bits < 16 || opt.counter_bits > 64))
    throw InputError(csv_path, 0, "counter width " + std::to_string(opt.counter_bits) + " bits: expected 16 to 64");
  if (!(opt.counter_to_s > 0.0)) throw InputError(csv_path, 0, "counter tick must be a positive number of seconds");
  const RtklibTimeTag tag = read_rtklib_time_tag(tag_path);
  TextFileLines lines(csv_path);
  TaggedImuCsvReport rep;
  DroppedRecords& dropped = rep.dropped;
  std::vector<RawSample> raw;
  std::vector<std::string_view> fields;
  std::string_view line;
  long long missing_crs = 0;  // lines ending in '\n' without '\r'
  uint64_t wrap_base = 0;     // added to every raw counter value (the wraps so far)
  uint64_t last_raw = 0;      // the last kept raw counter value
  int bits = opt.counter_bits;
  const double max_step_ticks = opt.max_counter_step_s / opt.counter_to_s;
  while (lines.next(line)) {
    const long line_no = lines.line_number();
    if (lines.last_line_terminated() && (line.empty() || line.back() != '\r')) ++missing_crs;
    split_fields(line, fields);
    if (fields.empty()) continue;
    if (!lines.last_line_terminated()) {  // the recording stopped mid-line
      dropped.add(DropReason::kMalformed, csv_path, line_no, "unterminated last line (cut)");
      continue;
    }
    if (fields.size() != 7) {
      dropped.add(DropReason::kWrongColumns, csv_path, line_no,
                  "expected 7 columns (ax,ay,az,gx,gy,gz,t_ms), found " + std::to_string(fields.size()));
      continue;
    }
    double v[6];
    uint64_t counter = 0;
    bool bad = false;
    for (int c = 0; c < 6 && !bad; ++c) {
      try {
        v[c] = parse_double(fields[c], csv_path, line_no, c + 1);
      } catch (const InputError& e) {
        if (line_no == 1) throw;  // a header or wrong file, not a cut line
        const bool non_finite = std::string(e.what()).find("finite") != std::string::npos;
        dropped.add(non_finite ? DropReason::kNonFinite : DropReason::kMalformed, csv_path, line_no,
                    "column " + std::to_string(c + 1) + ": expected a finite number, found '" +
                        std::string(fields[c].substr(0, 40)) + "'");
        bad = true;
      }
    }
    if (bad) continue;
    // No IMU measures this (1e5 g, 1e4 rad/s): a corrupted field, which would also overflow the increments.
    constexpr double kMaxAccel_mps2 = 1e6, kMaxRate_rad_s = 1e4;
    const Vec3 f = Vec3(v[0], v[1], v[2]) * opt.accel_to_mps2, w = Vec3(v[3], v[4], v[5]) * opt.gyro_to_rad_s;
    if (!(f.cwiseAbs().maxCoeff() <= kMaxAccel_mps2) || !(w.cwiseAbs().maxCoeff() <= kMaxRate_rad_s)) {
      dropped.add(DropReason::kOutOfRange, csv_path, line_no,
                  "specific force or rate beyond any IMU (|f| <= 1e6 m/s^2, |w| <= 1e4 rad/s)");
      continue;
    }
    bool too_large = false;
    if (!parse_counter(fields[6], counter, too_large)) {
      if (line_no == 1 && !too_large) throw InputError(csv_path, line_no, "column 7: expected the counter [ticks], found '" + std::string(fields[6].substr(0, 40)) + "'");
      dropped.add(too_large ? DropReason::kOutOfRange : DropReason::kMalformed, csv_path, line_no,
                  "column 7: expected an unsigned integer counter below 2^64, found '" +
                      std::string(fields[6].substr(0, 40)) + "'");
      continue;
    }
    if (bits > 0 && bits < 64 && counter >> bits != 0) {
      dropped.add(DropReason::kOutOfRange, csv_path, line_no,
                  "column 7: counter " + std::to_string(counter) + " wider than " + std::to_string(bits) + " bits");
      continue;
    }
    uint64_t unwrapped = wrap_base + counter;
    if (!raw.empty()) {
      if (counter == last_raw) {
        dropped.add(DropReason::kRepeated, csv_path, line_no, "counter repeats: " + std::to_string(counter));
        continue;
      }
      if (counter < last_raw) {
        // A counter that restarts near zero right after its largest values wrapped: unwrap it.
        int wrap_bits = 0;
        for (int k : {16, 24, 32, 64}) {
          if ((bits > 0 && k != bits) || (bits == 0 && k == 64)) continue;
          const uint64_t span = k == 64 ? 0 : (uint64_t{1} << k);  // 2^64 wraps to 0 in unsigned arithmetic
          if (k < 64 && last_raw >= span) continue;
          const uint64_t step = span - last_raw + counter;
          if (static_cast<double>(step) <= max_step_ticks) {
            wrap_bits = k;
            break;
          }
        }
        const bool jumped = raw.size() >= 2 && wrap_base + counter > raw[raw.size() - 2].counter;
        if (jumped) {  // the sample before ran ahead of both neighbours: its counter was corrupted
          dropped.add(DropReason::kTimeJump, csv_path, raw.back().line,
                      "counter ahead of both neighbours (" + std::to_string(raw[raw.size() - 2].counter) + ", " +
                          std::to_string(unwrapped) + ")");
          raw.pop_back();
        } else if (wrap_bits > 0) {
          wrap_base += wrap_bits == 64 ? 0 : (uint64_t{1} << wrap_bits);
          unwrapped = wrap_base + counter;
          bits = wrap_bits;
          ++rep.counter_wraps;
        } else {
          dropped.add(DropReason::kTimeBackwards, csv_path, line_no,
                      "counter goes backwards: " + std::to_string(counter) + " after " + std::to_string(last_raw));
          continue;
        }
      }
      if (static_cast<double>(unwrapped - raw.back().counter) > max_step_ticks) {
        dropped.add(DropReason::kOutOfRange, csv_path, line_no,
                    "counter jumps by " + std::to_string(unwrapped - raw.back().counter) + " ticks (more than " +
                        std::to_string(opt.max_counter_step_s) + " s)");
        continue;
      }
    }
    const double counter_s = raw.empty() ? 0.0 : static_cast<double>(unwrapped - raw.front().counter) * opt.counter_to_s;
    raw.push_back({counter_s, unwrapped, lines.line_end_offset(), line_no, missing_crs, f, w});
    last_raw = counter;
  }
  rep.counter_bits = bits;
  const long data_lines = static_cast<long>(raw.size()) + dropped.total();
  if (dropped.total() > opt.max_dropped_fraction * static_cast<double>(data_lines) && dropped.total() > 2)
    throw InputError(csv_path, 0, std::to_string(dropped.total()) + " of " + std::to_string(data_lines) +
                                      " data lines dropped (expected ax,ay,az,gx,gy,gz,t_ms): " + dropped.describe());
  if (raw.size() < 3) throw InputError(csv_path, 0, "fewer than 3 complete IMU samples (expected ax,ay,az,gx,gy,gz,t_ms)");
  // Each popped time jump left the next sample's relative counter measured from a stale first sample: recompute.
  for (auto& x : raw) x.counter_s = static_cast<double>(x.counter - raw.front().counter) * opt.counter_to_s;

  // Reception times, in the line-end convention the tag positions count.
  const unsigned long long stored_size = lines.line_end_offset() + (lines.last_line_terminated() ? 1 : 0);
  const bool crlf = tags_count_crlf(tag, stored_size, missing_crs, csv_path, tag_path);
  rep.line_ends = crlf ? "CRLF (as recorded; the stored file has LF: one CR per line added to the positions)"
                       : "as stored";
  rep.crlf_added_bytes = crlf ? missing_crs : 0;
  for (auto& x : raw)
    x.reception_gps_s = tag.reception_gps_s(x.end_offset + (crlf ? static_cast<unsigned long long>(x.crs_through) : 0));

  double offset = 0, rate = 1;
  fit_lower_envelope(raw, offset, rate);
  rep.host_rate_error_ppm = (rate - 1.0) * 1e6;
  rep.rate_source = "host reception times (lower envelope)";
  const bool given = opt.counter_rate > 0.0;
  // A counter off by more than a crystal can be means the reception times are distorted (a host that buffered
  // the stream, or tag positions in another line-end convention than detected), not the counter: keep the
  // counter's nominal rate.
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
  // Seconds of the first sample's week, going on past 604800 after a rollover (the KF-GINS convention): the seconds
  // of each sample's own week went back by a week there (found by the fuzzer: a counter that ran 16777 s on).
  const double first_week_s = GpsTime::from_total_seconds(offset + rate * raw[1].counter_s).week * kSecondsPerWeek;
  for (size_t k = 1; k < raw.size(); ++k) {
    const double t1 = offset + rate * raw[k].counter_s;
    ImuIncrement inc;
    inc.t_s = t1 - first_week_s;
    inc.dt_s = rate * (raw[k].counter_s - raw[k - 1].counter_s);  // not t1 - t0: 1e9 s absolute times lose digits
    inc.dtheta_b_rad = 0.5 * (raw[k - 1].w_b_rad_s + raw[k].w_b_rad_s) * inc.dt_s;
    inc.dvel_b_mps = 0.5 * (raw[k - 1].f_b_mps2 + raw[k].f_b_mps2) * inc.dt_s;
    out.push_back(inc);
  }
  rep.distinct_sample_tags_s.clear();
  rep.repeated_rows = 0;
  for (size_t k = 0; k < raw.size(); ++k) {
    if (k > 0 && raw[k].w_b_rad_s == raw[k - 1].w_b_rad_s && raw[k].f_b_mps2 == raw[k - 1].f_b_mps2) {
      ++rep.repeated_rows;
      continue;
    }
    rep.distinct_sample_tags_s.push_back(offset + rate * raw[k].counter_s - first_week_s);
  }
  std::vector<long> line_of;  // of each increment: the line of the sample that ends it
  line_of.reserve(out.size());
  for (size_t k = 1; k < raw.size(); ++k) line_of.push_back(raw[k].line);
  const ImuGapSummary g = find_imu_gaps(out, line_of);
  rep.gaps = g.gaps;
  rep.long_gaps = g.long_gaps;
  rep.longest_gap_s = g.longest_gap_s;
  rep.samples = static_cast<long>(raw.size());
  rep.skipped_lines = dropped[DropReason::kMalformed] + dropped[DropReason::kWrongColumns] + dropped[DropReason::kNonFinite];
  rep.skipped_counter = dropped.total() - rep.skipped_lines;
  if (report) *report = rep;
  return out;
}

}  // namespace ldv
