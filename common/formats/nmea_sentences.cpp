#include "common/formats/nmea_sentences.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::gnss {
namespace {
constexpr double kKnotToMps = 1852.0 / 3600.0;
constexpr double kKmhToMps = 1.0 / 3.6;

std::vector<std::string_view> split_commas(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::optional<double> number(std::string_view f) {
  if (f.empty()) return std::nullopt;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<int> integer(std::string_view f) {
  if (f.empty()) return std::nullopt;
  int v = 0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (ec != std::errc() || end != f.data() + f.size()) return std::nullopt;
  return v;
}

// "hhmmss.sss" -> seconds of day.
std::optional<double> time_of_day(std::string_view f) {
  if (f.size() < 6) return std::nullopt;
  const auto h = integer(f.substr(0, 2)), m = integer(f.substr(2, 2));
  const auto s = number(f.substr(4));
  if (!h || !m || !s || *h > 23 || *m > 59 || *s < 0.0 || *s >= 61.0) return std::nullopt;
  return *h * 3600.0 + *m * 60.0 + *s;
}

// "ddmm.mmmm" / "dddmm.mmmm" plus hemisphere -> radians.
std::optional<double> angle(std::string_view value, std::string_view hemisphere, char positive, char negative,
                            double max_deg) {
  const auto v = number(value);
  if (!v || *v < 0.0 || hemisphere.size() != 1) return std::nullopt;
  const double deg = std::floor(*v / 100.0);
  const double minutes = *v - deg * 100.0;
  const double total_deg = deg + minutes / 60.0;
  if (minutes >= 60.0 || total_deg > max_deg) return std::nullopt;
  if (hemisphere[0] == positive) return total_deg * kDegToRad;
  if (hemisphere[0] == negative) return -total_deg * kDegToRad;
  return std::nullopt;
}

// Splits and checks the sentence type; fields[0] is the address.
std::optional<std::vector<std::string_view>> fields_of(std::string_view sentence, std::string_view type,
                                                       std::size_t min_fields) {
  const auto address = nmea_address(sentence);
  if (!address || address->type != type) return std::nullopt;
  auto fields = split_commas(sentence);
  if (fields.size() < min_fields) return std::nullopt;
  return fields;
}

// A day that exists in the Gregorian calendar (no 31 February, 29 February in leap years only).
bool valid_date(const UtcDate& d) {
  if (d.month < 1 || d.month > 12 || d.day < 1) return false;
  static constexpr int kDaysInMonth[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (d.year % 4 == 0 && d.year % 100 != 0) || d.year % 400 == 0;
  return d.day <= kDaysInMonth[d.month - 1] + (d.month == 2 && leap ? 1 : 0);
}
}  // namespace

std::optional<NmeaAddress> nmea_address(std::string_view sentence) {
  const std::string_view address = sentence.substr(0, sentence.find(','));
  if (address.size() < 2) return std::nullopt;
  if (address[0] == 'P') return NmeaAddress{address.substr(0, 1), address.substr(1)};
  if (address.size() != 5) return std::nullopt;
  return NmeaAddress{address.substr(0, 2), address.substr(2)};
}

std::optional<NmeaGga> parse_gga(std::string_view sentence) {
  // GGA,time,lat,N,lon,E,quality,numsats,hdop,alt,M,sep,M,age,station
  const auto f = fields_of(sentence, "GGA", 15);
  if (!f) return std::nullopt;
  NmeaGga g;
  const auto tod = time_of_day((*f)[1]);
  const auto q = integer((*f)[6]);
  if (!tod || !q) return std::nullopt;
  g.utc_seconds_of_day = *tod;
  g.quality_code = *q;
  g.num_sats = integer((*f)[7]).value_or(0);
  g.hdop = number((*f)[8]).value_or(0.0);
  g.correction_age_s = number((*f)[13]);
  if ((*f)[2].empty() && (*f)[4].empty()) return g;  // no fix yet
  const auto lat = angle((*f)[2], (*f)[3], 'N', 'S', 90.0);
  const auto lon = angle((*f)[4], (*f)[5], 'E', 'W', 180.0);
  const auto alt = number((*f)[9]);
  if (!lat || !lon || !alt) return std::nullopt;
  g.has_position = true;
  g.lat_rad = *lat;
  g.lon_rad = *lon;
  g.altitude_msl_m = *alt;
  g.geoid_separation_m = number((*f)[11]).value_or(0.0);
  return g;
}

std::optional<NmeaGst> parse_gst(std::string_view sentence) {
  // GST,time,rms,semi-major,semi-minor,orientation,lat std,lon std,alt std
  const auto f = fields_of(sentence, "GST", 9);
  if (!f) return std::nullopt;
  NmeaGst g;
  const auto tod = time_of_day((*f)[1]);
  const auto lat_std = number((*f)[6]), lon_std = number((*f)[7]), alt_std = number((*f)[8]);
  if (!tod || !lat_std || !lon_std || !alt_std || *lat_std < 0 || *lon_std < 0 || *alt_std < 0) return std::nullopt;
  g.utc_seconds_of_day = *tod;
  g.range_rms_m = number((*f)[2]).value_or(0.0);
  g.semi_major_std_m = number((*f)[3]).value_or(0.0);
  g.semi_minor_std_m = number((*f)[4]).value_or(0.0);
  g.semi_major_orientation_rad = number((*f)[5]).value_or(0.0) * kDegToRad;
  g.lat_std_m = *lat_std;
  g.lon_std_m = *lon_std;
  g.alt_std_m = *alt_std;
  return g;
}

std::optional<NmeaRmc> parse_rmc(std::string_view sentence) {
  // RMC,time,status,lat,N,lon,E,speed kn,course,ddmmyy,magvar,E/W[,mode[,nav status]]
  const auto f = fields_of(sentence, "RMC", 12);
  if (!f) return std::nullopt;
  NmeaRmc r;
  const auto tod = time_of_day((*f)[1]);
  const std::string_view date = (*f)[9];
  if (!tod || date.size() != 6) return std::nullopt;
  const auto dd = integer(date.substr(0, 2)), mm = integer(date.substr(2, 2)), yy = integer(date.substr(4, 2));
  if (!dd || !mm || !yy) return std::nullopt;
  // Two-digit year: NMEA has no century; GNSS receivers print dates after 1980.
  r.date = {*yy < 80 ? 2000 + *yy : 1900 + *yy, *mm, *dd};
  if (!valid_date(r.date)) return std::nullopt;
  r.utc_seconds_of_day = *tod;
  r.valid = (*f)[2] == "A";
  r.speed_mps = number((*f)[7]).value_or(0.0) * kKnotToMps;
  if (const auto course = number((*f)[8])) r.course_true_rad = *course * kDegToRad;
  if (f->size() > 12 && (*f)[12].size() == 1) r.mode = (*f)[12][0];
  if ((*f)[3].empty() && (*f)[5].empty()) return r;
  const auto lat = angle((*f)[3], (*f)[4], 'N', 'S', 90.0);
  const auto lon = angle((*f)[5], (*f)[6], 'E', 'W', 180.0);
  if (!lat || !lon) return std::nullopt;
  r.has_position = true;
  r.lat_rad = *lat;
  r.lon_rad = *lon;
  return r;
}

std::optional<NmeaVtg> parse_vtg(std::string_view sentence) {
  // VTG,course true,T,course magnetic,M,speed kn,N,speed km/h,K[,mode]
  const auto f = fields_of(sentence, "VTG", 9);
  if (!f) return std::nullopt;
  NmeaVtg v;
  if (const auto course = number((*f)[1])) v.course_true_rad = *course * kDegToRad;
  if (const auto kmh = number((*f)[7])) {
    v.speed_mps = *kmh * kKmhToMps;
  } else if (const auto kn = number((*f)[5])) {
    v.speed_mps = *kn * kKnotToMps;
  } else {
    return std::nullopt;
  }
  if (f->size() > 9 && (*f)[9].size() == 1) v.mode = (*f)[9][0];
  return v;
}

std::optional<NmeaZda> parse_zda(std::string_view sentence) {
  // ZDA,time,dd,mm,yyyy,zone hours,zone minutes
  const auto f = fields_of(sentence, "ZDA", 5);
  if (!f) return std::nullopt;
  NmeaZda z;
  const auto tod = time_of_day((*f)[1]);
  const auto dd = integer((*f)[2]), mm = integer((*f)[3]), yyyy = integer((*f)[4]);
  if (!tod || !dd || !mm || !yyyy) return std::nullopt;
  z.utc_seconds_of_day = *tod;
  z.date = {*yyyy, *mm, *dd};
  if (!valid_date(z.date) || z.date.year < 1980) return std::nullopt;
  return z;
}

}  // namespace ldv::gnss
