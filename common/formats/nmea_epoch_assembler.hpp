#pragma once
// Groups the NMEA sentences of one receiver epoch (same UTC time tag) into one GnssSolution:
// GGA gives position, quality, satellites and age; GST the position standard deviations; RMC or
// ZDA the date; RMC or VTG the horizontal velocity. Also turns whole-second RMC/ZDA time tags into
// PPS labels. Converts UTC to GPS time with a configured leap-second count.
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "common/formats/gnss_solution.hpp"
#include "common/formats/nmea_sentences.hpp"

namespace ldv::gnss {

struct NmeaEpochOptions {
  // GPS - UTC [s]: 18 since 2017-01-01. NMEA carries no leap-second count; when the receiver also
  // speaks UBX, take it from there.
  double gps_minus_utc_s = 18.0;
  // Position std [m] per axis used when the receiver sends no GST, indexed by GnssQuality
  // (fixed, float, sbas, dgps, single, ppp). Typical, not measured: configure per receiver.
  double default_std_m[6] = {0.02, 0.3, 1.0, 1.0, 3.0, 0.1};
  // NMEA carries no velocity accuracy and no vertical velocity.
  double horizontal_velocity_std_mps = 0.1;
  double vertical_velocity_std_mps = 10.0;
};

// GGA fix quality indicator -> our quality; nullopt for 0 (invalid) and for 6/7/8 (dead
// reckoning, manual input, simulator), which are not GNSS measurements.
std::optional<GnssQuality> quality_from_gga(int quality_code);

struct NmeaEpochCounters {
  std::uint64_t solutions = 0;          // emitted
  std::uint64_t labels = 0;             // PPS labels emitted
  std::uint64_t malformed = 0;          // known sentence type whose fields did not parse
  std::uint64_t ignored = 0;            // other sentence types (GSA, GSV, GLL, TXT, ...)
  std::uint64_t epochs_without_fix = 0; // no GGA, or GGA without a valid fix
  std::uint64_t epochs_without_date = 0;// no RMC/ZDA seen yet: GPS week unknown
};

class NmeaEpochAssembler {
 public:
  using SolutionHandler = std::function<void(const GnssSolution&)>;
  using LabelHandler = std::function<void(const PpsTimeLabel&)>;

  explicit NmeaEpochAssembler(SolutionHandler on_solution, LabelHandler on_label = {},
                              NmeaEpochOptions options = {});

  // Feed every checksum-verified sentence (NmeaFramer's callback).
  void on_sentence(std::string_view sentence);
  // Emits the epoch in progress (end of file, or a quiet link).
  void flush();
  const NmeaEpochCounters& counters() const { return counters_; }

 private:
  enum Part : unsigned { kGga = 1, kGst = 2, kRmc = 4, kVtg = 8, kZda = 16 };
  struct Epoch {
    std::int64_t key_ms = -1;  // UTC time of day [ms]
    double utc_seconds_of_day = 0.0;
    unsigned parts = 0;
    bool emitted = false;
    std::optional<NmeaGga> gga;
    std::optional<NmeaGst> gst;
    std::optional<UtcDate> date;
    std::optional<double> speed_mps, course_rad;
  };

  void enter_epoch(double utc_seconds_of_day);
  void add_part(Part p);
  void emit_label(const UtcDate& date, double utc_seconds_of_day);
  void close_epoch();
  std::optional<GpsTime> gps_time_of(const Epoch& e);

  SolutionHandler on_solution_;
  LabelHandler on_label_;
  NmeaEpochOptions options_;
  NmeaEpochCounters counters_;
  Epoch epoch_;
  unsigned previous_parts_ = 0;  // the sentence set the receiver sent last epoch
  std::optional<UtcDate> last_date_;
  double last_date_seconds_of_day_ = 0.0;
  std::optional<GpsTime> last_label_;
};

}  // namespace ldv::gnss
