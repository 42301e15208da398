// A user's own tables (common/io/delimited_table, input/tables/): whatever the bytes of the data file, an InputError
// naming it, or IMU increments and GNSS fixes whose times strictly increase and whose values are finite (a std
// positive, a latitude within +-90 deg). The first byte picks the description: columns by 1-based index or by the
// names a header would give, rates or increments, a time column (seconds, a date-time, a date and a time of day) or the
// row index, geodetic or ECEF.
#include <cmath>

#include "common/config/config_section.hpp"
#include "common/io/input_error.hpp"
#include "input/tables/gnss_table.hpp"
#include "input/tables/imu_table.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

namespace {
config::ConfigSection section(const std::string& yaml) { return config::ConfigSection(YAML::Load(yaml), "fuzz.yaml"); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fuzz::input_file(data + 1, size - 1);
  const int mode = data[0];
  // 32: a date-time column (column 1, UTC); 64: date and time of day in two fields (columns 8 and 9, GPST)
  const std::string time = mode & 64   ? "{date_column: 8, column: 9, format: gpst}"
                           : mode & 32 ? "{column: 1, format: utc}"
                           : mode & 1  ? "{row_period_s: 0.01, offset_s: 100}"
                                       : "{column: 1, unit: ms}";
  try {
    if (mode & 2) {
      const std::string by = mode & 4 ? "[gx, gy, gz]" : "[2, 3, 4]";
      const std::string acc = mode & 4 ? "[ax, ay, az]" : "[5, 6, 7]";
      const input::ImuTable t = input::ImuTable::from(
          section("path: " + path + "\ntime: " + time + "\ngyro: {columns: " + by +
                  ", unit: " + (mode & 8 ? "rad" : "deg/s") + "}\naccel: {columns: " + acc +
                  ", unit: g}\naxes: [1, -2, -3]\n" + (mode & 16 ? "sample: interval_mean\n" : "")),
          "fuzz.yaml");
      const auto imu = input::read_imu_table(t);
      for (size_t i = 0; i < imu.size(); ++i) {
        fuzz::require(std::isfinite(imu[i].t_s) && std::isfinite(imu[i].dt_s) && imu[i].dt_s > 0 &&
                          imu[i].dtheta_b_rad.allFinite() && imu[i].dvel_b_mps.allFinite(),
                      "imu_table: an increment not finite");
        if (i > 0) fuzz::require(imu[i].t_s > imu[i - 1].t_s, "imu_table: times not increasing");
      }
    } else {
      const std::string pos = mode & 4 ? "[lat, lon, h]" : "[2, 3, 4]";
      const input::GnssTable t = input::GnssTable::from(
          section("path: " + path + "\ntime: " + time + "\nposition: {columns: " + pos +
                  (mode & 8 ? ", frame: ecef" : "") + "}\n" +
                  (mode & 16 ? "std: {columns: [5, 6, 7]}\nquality: {column: 8, fixed: [4], float: [5]}\n"
                             : "std_m: [0.02, 0.02, 0.04]\n")),
          "fuzz.yaml");
      const auto gnss = input::read_gnss_table(t);
      for (size_t i = 0; i < gnss.size(); ++i) {
        fuzz::require(std::isfinite(gnss[i].t_s) && std::isfinite(gnss[i].pos.lat_rad) &&
                          std::isfinite(gnss[i].pos.lon_rad) && std::isfinite(gnss[i].pos.h_m) &&
                          std::abs(gnss[i].pos.lat_rad) <= M_PI / 2 + 1e-12,
                      "gnss_table: a position not finite or beyond the pole");
        fuzz::require(gnss[i].pos_std_ned_m.allFinite() && (gnss[i].pos_std_ned_m.array() > 0).all(),
                      "gnss_table: a std not positive and finite");
        if (i > 0) fuzz::require(gnss[i].t_s > gnss[i - 1].t_s, "gnss_table: times not increasing");
      }
    }
  } catch (const InputError&) {
  }
  return 0;
}
