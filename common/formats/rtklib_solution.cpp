#include "common/formats/rtklib_solution.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"
#include "common/io/text_table.hpp"
#include "common/logging.hpp"
#include "common/math/rotation.hpp"

namespace ldv::gnss {
namespace {

std::optional<double> rtklib_number(std::string_view f) {
  if (!f.empty() && f[0] == '+') f.remove_prefix(1);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (f.empty() || ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// RTKLIB prints covariances as sign(c) * sqrt(|c|).
double covariance_from_signed_sqrt(double s) { return s < 0 ? -s * s : s * s; }

// Symmetric 3x3 from RTKLIB's (s11 s22 s33 s12 s23 s31) signed-sqrt columns.
Mat3 covariance_from_columns(const double* s) {
  Mat3 c;
  c(0, 0) = covariance_from_signed_sqrt(s[0]);
  c(1, 1) = covariance_from_signed_sqrt(s[1]);
  c(2, 2) = covariance_from_signed_sqrt(s[2]);
  c(0, 1) = c(1, 0) = covariance_from_signed_sqrt(s[3]);
  c(1, 2) = c(2, 1) = covariance_from_signed_sqrt(s[4]);
  c(2, 0) = c(0, 2) = covariance_from_signed_sqrt(s[5]);
  return c;
}

// Axis permutations into NED: (n, e, u) and (e, n, u) orderings.
Mat3 ned_from_neu() { return Vec3(1.0, 1.0, -1.0).asDiagonal(); }
Mat3 ned_from_enu() {
  Mat3 m;
  m << 0, 1, 0,  //
      1, 0, 0,   //
      0, 0, -1;
  return m;
}

// Parses "yyyy/mm/dd hh:mm:ss.sss" or "week tow" from two fields.
std::optional<GpsTime> parse_time(std::string_view a, std::string_view b) {
  if (a.find('/') != std::string_view::npos) {
    int y = 0, mo = 0, d = 0, h = 0, mi = 0;
    double s = 0.0;
    const std::string date(a), clock(b);
    char tail = 0;
    if (std::sscanf(date.c_str(), "%d/%d/%d%c", &y, &mo, &d, &tail) != 3) return std::nullopt;
    if (std::sscanf(clock.c_str(), "%d:%d:%lf%c", &h, &mi, &s, &tail) != 3) return std::nullopt;
    // Years a GNSS solution can carry (and no int overflow in the week count of a year 2147483647).
    if (y < 1980 || y > 2200 || mo < 1 || mo > 12 || d < 1 || d > 31 || h < 0 || h > 23 || mi < 0 || mi > 59 ||
        s < 0 || s >= 61)
      return std::nullopt;
    // Midnight first, then the clock time: keeps sub-microsecond resolution in sow_s.
    GpsTime t = gps_from_calendar({y, mo, d, 0, 0, 0.0});
    t.sow_s += h * 3600.0 + mi * 60.0 + s;
    return t;
  }
  const auto week = rtklib_number(a), tow = rtklib_number(b);
  // A week beyond any int is refused before the cast (99999999999 overflowed it); gnss::implausibility judges
  // the rest.
  if (!week || !tow || *week < 0 || *week > 1e8 || *week != std::floor(*week) || *tow < 0 ||
      *tow >= kSecondsPerWeek + 1)
    return std::nullopt;
  return GpsTime{static_cast<int>(*week), *tow};
}

// Brings sow_s back into [0, 604800) after adding seconds.
GpsTime normalized(GpsTime t) {
  const double weeks = std::floor(t.sow_s / kSecondsPerWeek);
  t.week += static_cast<int>(weeks);
  t.sow_s -= weeks * kSecondsPerWeek;
  return t;
}

// "35 08 04.917" style (RTKLIB -g): degrees carry the sign.
std::optional<double> dms_deg(std::string_view d, std::string_view m, std::string_view s) {
  const auto dv = rtklib_number(d), mv = rtklib_number(m), sv = rtklib_number(s);
  if (!dv || !mv || !sv) return std::nullopt;
  const double sign = d.starts_with('-') ? -1.0 : 1.0;
  return sign * (std::abs(*dv) + *mv / 60.0 + *sv / 3600.0);
}
}  // namespace

RtklibSolutionParser::RtklibSolutionParser(RtklibParserOptions options) : options_(std::move(options)) {}

void RtklibSolutionParser::parse_header(std::string_view line) {
  // Column header: "%  GPST   latitude(deg) ..." / "x-ecef(m)" / "e-baseline(m)" / "latitude(d'\")".
  if (line.find("latitude(d'") != std::string_view::npos) options_.layout = RtklibPositionLayout::kLatLonDms;
  else if (line.find("latitude(deg)") != std::string_view::npos) options_.layout = RtklibPositionLayout::kLatLonDeg;
  else if (line.find("x-ecef(m)") != std::string_view::npos) options_.layout = RtklibPositionLayout::kEcef;
  else if (line.find("e-baseline(m)") != std::string_view::npos) options_.layout = RtklibPositionLayout::kEnuBaseline;
  if (line.find("latitude(") != std::string_view::npos || line.find("-ecef(") != std::string_view::npos ||
      line.find("-baseline(") != std::string_view::npos) {
    utc_ = line.find("UTC") != std::string_view::npos;
  }
  // "% ref pos   : lat lon h" (degrees) or "x y z" (ECEF): the base of baseline outputs.
  const std::size_t ref = line.find("ref pos");
  if (ref != std::string_view::npos) {
    const std::size_t colon = line.find(':', ref);
    if (colon == std::string_view::npos) return;
    split_fields(line.substr(colon + 1), fields_);
    if (fields_.size() < 3) return;
    const auto a = rtklib_number(fields_[0]), b = rtklib_number(fields_[1]), c = rtklib_number(fields_[2]);
    if (!a || !b || !c) return;
    const Vec3 v(*a, *b, *c);
    options_.base_ecef_m = v.norm() > 1e6 ? v : earth::ecef_from_geodetic({*a * kDegToRad, *b * kDegToRad, *c});
  }
}

RtklibSolutionParser::LineKind RtklibSolutionParser::parse_line(std::string_view line, GnssSolution& out,
                                                                std::string* why) {
  auto malformed = [&](const char* reason) {
    if (why) *why = reason;
    return LineKind::kMalformed;
  };
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.remove_suffix(1);
  split_fields(line, fields_);
  if (fields_.empty()) return LineKind::kEmpty;
  if (fields_[0].starts_with('%')) {
    parse_header(line);
    return LineKind::kHeader;
  }
  if (fields_.size() < 2) return malformed("expected a time in two fields");
  const auto time = parse_time(fields_[0], fields_[1]);
  if (!time) return malformed("expected 'yyyy/mm/dd hh:mm:ss' or 'week tow'");

  // Position: 3 values (7 for "d m s d m s h"), then the solution columns.
  RtklibPositionLayout layout = options_.layout;
  const std::size_t pos_fields = layout == RtklibPositionLayout::kLatLonDms ? 7 : 3;
  const std::size_t first = 2 + pos_fields;
  constexpr std::size_t kSolutionColumns = 10;  // Q ns 6 x sd age ratio
  constexpr std::size_t kVelocityColumns = 9;   // 3 velocity + 6 sd
  if (fields_.size() < first + kSolutionColumns) return malformed("too few columns");
  const bool has_velocity = fields_.size() >= first + kSolutionColumns + kVelocityColumns;

  double v[3 + kSolutionColumns + kVelocityColumns] = {};
  if (layout == RtklibPositionLayout::kLatLonDms) {
    const auto lat = dms_deg(fields_[2], fields_[3], fields_[4]), lon = dms_deg(fields_[5], fields_[6], fields_[7]);
    const auto h = rtklib_number(fields_[8]);
    if (!lat || !lon || !h) return malformed("expected a number in the position columns");
    v[0] = *lat, v[1] = *lon, v[2] = *h;
  } else {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto x = rtklib_number(fields_[2 + k]);
      if (!x) return malformed("expected a number in the position columns");
      v[k] = *x;
    }
  }
  const std::size_t n_rest = kSolutionColumns + (has_velocity ? kVelocityColumns : 0);
  for (std::size_t k = 0; k < n_rest; ++k) {
    const auto x = rtklib_number(fields_[first + k]);
    if (!x) return malformed("expected a number in the solution columns");
    v[3 + k] = *x;
  }
  if (layout == RtklibPositionLayout::kUnknown) {
    // No header: an ECEF position is ~6.4e6 m from the centre; lat/lon/h never is.
    layout = Vec3(v[0], v[1], v[2]).norm() > 1e6 ? RtklibPositionLayout::kEcef : RtklibPositionLayout::kLatLonDeg;
  }

  // Ranges checked before the casts: a Q or a satellite count of 1e300 does not fit an int (undefined behaviour).
  if (!(v[3] >= 1.0 && v[3] <= 6.0) || v[3] != std::floor(v[3])) return malformed("expected Q in 1..6");
  if (!(v[4] >= 0.0 && v[4] <= 1000.0)) return malformed("expected a satellite count in 0..1000");
  const int q = static_cast<int>(v[3]);
  GnssSolution s;
  s.time = normalized(utc_ ? GpsTime{time->week, time->sow_s + options_.gps_minus_utc_s} : *time);
  GnssFix& f = s.fix;
  f.t_s = s.time.sow_s;
  f.quality = static_cast<GnssQuality>(q);  // RTKLIB's Q and GnssQuality share the numbering
  f.num_sats = static_cast<int>(v[4]);
  f.age_s = v[11];
  f.ratio = v[12];
  const Mat3 cov_pos = covariance_from_columns(&v[5]);
  const Vec3 vel = has_velocity ? Vec3(v[13], v[14], v[15]) : Vec3::Zero();
  const Mat3 cov_vel = has_velocity ? covariance_from_columns(&v[16]) : Mat3::Identity();

  Mat3 R_to_ned;  // from the file's axes to NED at the solution
  switch (layout) {
    case RtklibPositionLayout::kLatLonDeg:
    case RtklibPositionLayout::kLatLonDms:
      if (std::abs(v[0]) > 90.0 || std::abs(v[1]) > 360.0) return malformed("latitude/longitude out of range");
      f.pos = {v[0] * kDegToRad, v[1] * kDegToRad, v[2]};
      R_to_ned = ned_from_neu();
      break;
    case RtklibPositionLayout::kEcef: {
      const Vec3 r_e(v[0], v[1], v[2]);
      if (r_e.norm() < 1e6) return malformed("ECEF position too close to the Earth's centre");
      f.pos = earth::geodetic_from_ecef(r_e);
      R_to_ned = earth::C_n_e(f.pos).transpose();
      break;
    }
    case RtklibPositionLayout::kEnuBaseline: {
      if (!options_.base_ecef_m) return malformed("e/n/u baseline without a base position ('% ref pos' or options)");
      const Geodetic base = earth::geodetic_from_ecef(*options_.base_ecef_m);
      const Vec3 baseline_ned = ned_from_enu() * Vec3(v[0], v[1], v[2]);
      f.pos = earth::geodetic_from_ecef(*options_.base_ecef_m + earth::C_n_e(base) * baseline_ned);
      R_to_ned = ned_from_enu();
      break;
    }
    case RtklibPositionLayout::kUnknown: return malformed("unknown layout");
  }
  // The file's own sigmas (sdn sde sdu, or sdx sdy sdz): a zero or negative one is no solution RTKLIB writes
  // (it prints sqrt of a variance), and would make the filter refuse, or trust blindly, every fix.
  if (!(v[5] > 0.0 && v[6] > 0.0 && v[7] > 0.0)) return malformed("position sigma not positive");
  if (has_velocity && (v[16] < 0.0 || v[17] < 0.0 || v[18] < 0.0)) return malformed("velocity sigma negative");
  s.pos_cov_ned_m2 = R_to_ned * cov_pos * R_to_ned.transpose();
  sync_std_from_cov(s);
  if (has_velocity) {
    f.has_velocity = true;
    f.vel_n_mps = R_to_ned * vel;
    f.vel_std_n_mps = (R_to_ned * cov_vel * R_to_ned.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  out = s;
  return LineKind::kSolution;
}

std::string RtklibReadReport::summary() const {
  std::string s = std::to_string(solutions) + " solutions";
  for (const auto& [why, count] : malformed_by_reason) {
    const auto line = first_line_by_reason.find(why);
    s += ", " + std::to_string(count) + " malformed (" + why +
         (line != first_line_by_reason.end() ? ", first at line " + std::to_string(line->second) : std::string()) + ")";
  }
  return s;
}

std::vector<GnssSolution> read_rtklib_pos(const std::string& path, RtklibParserOptions options,
                                          RtklibReadReport* report) {
  TextFileLines in(path);  // bounded lines; a device (/dev/zero) or a directory is refused
  RtklibSolutionParser parser(std::move(options));
  std::vector<GnssSolution> out;
  RtklibReadReport rep;
  std::string why;
  std::string_view line;
  long line_no = 0, first_malformed_line = 0;
  std::string first_why;
  GnssSolution s;
  constexpr long kLoggedLines = 10;  // each malformed line up to this many, then only the counts
  while (in.next(line)) {
    line_no = in.line_number();
    const auto kind = parser.parse_line(line, s, &why);
    if (kind == RtklibSolutionParser::LineKind::kMalformed) {
      if (rep.malformed() < kLoggedLines) spdlog::warn("{}:{}: RTKLIB solution line skipped: {}", path, line_no, why);
      if (rep.malformed() == 0) first_malformed_line = line_no, first_why = why;
      if (!rep.first_line_by_reason.count(why)) rep.first_line_by_reason[why] = line_no;
      ++rep.malformed_by_reason[why];
    }
    // What no receiver writes (a week of 1980, a height of 1e300 m): the checks of every decoder's output.
    if (kind == RtklibSolutionParser::LineKind::kSolution) {
      if (const auto bad = implausibility(s)) {
        why = "implausible: " + *bad;
        if (rep.malformed() < kLoggedLines) spdlog::warn("{}:{}: RTKLIB solution line skipped: {}", path, line_no, why);
        if (rep.malformed() == 0) first_malformed_line = line_no, first_why = why;
        if (!rep.first_line_by_reason.count(why)) rep.first_line_by_reason[why] = line_no;
        ++rep.malformed_by_reason[why];
        continue;
      }
      out.push_back(s);
    }
  }
  rep.solutions = static_cast<long>(out.size());
  if (rep.malformed() > kLoggedLines) spdlog::warn("{}: {}", path, rep.summary());
  if (out.empty() && rep.malformed() > 0)
    throw InputError(path, first_malformed_line, "RTKLIB solution line: " + first_why + "; no usable solution (" + rep.summary() + ")");
  // As the KF-GINS readers: more than 10 % of the solution lines malformed is a wrong file, not noise to count.
  const long lines_with_data = rep.solutions + rep.malformed();
  if (static_cast<double>(rep.malformed()) > kMaxMalformedFraction * static_cast<double>(lines_with_data))
    throw InputError(path, first_malformed_line,
                     "RTKLIB solution line: " + first_why + "; " + std::to_string(rep.malformed()) + " of " +
                         std::to_string(lines_with_data) + " solution lines malformed (more than 10 %): " +
                         rep.summary());
  if (report) *report = rep;
  return out;
}

}  // namespace ldv::gnss
