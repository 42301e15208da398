#pragma once
// Odometer text file, KF-GINS style (odo.txt): one sample per line, two columns
//   sow speed_mps
// sow = GPS seconds of week of the measurement instant (the time base of imu.txt and gnss.txt), speed =
// forward speed of the vehicle [m/s] (vehicle-frame x of the velocity of the odometer point; negative when
// reversing). Empty lines and lines starting with '#' or '%' are comments.
#include <string>
#include <vector>

namespace ldv {

struct OdometerSample {
  double t_s = 0.0;        // GPS seconds of week
  double speed_mps = 0.0;  // forward speed, vehicle x [m/s]
};

// Strict: a line with another number of columns, a field that is not a finite number, a time outside
// [0, 604800) s or not after the previous line's raises InputError naming file:line and what was expected.
std::vector<OdometerSample> read_odometer_text(const std::string& path);
// Throws InputError on a write error or a non-finite value.
void write_odometer_text(const std::string& path, const std::vector<OdometerSample>& samples);

}  // namespace ldv
