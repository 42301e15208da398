// RTKLIB files: the .pos solution file and the tagged CSV with its .tag time-tag file (the input split at the
// length bytes 1-2 give). Either an InputError naming the file, or solutions every decoder check passes and
// IMU samples whose times increase.
#include <algorithm>
#include <cmath>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  try {
    if (data[0] % 2 == 0) {
      const std::string path = fuzz::input_file(data + 1, size - 1, "pos");
      for (const gnss::GnssSolution& s : gnss::read_rtklib_pos(path))
        fuzz::require(!gnss::implausibility(s), ".pos: an implausible solution was kept");
    } else {
      // Bytes 1-2: the tag file's length (little-endian); the tag file, then the CSV.
      const size_t tag_bytes = std::min<size_t>(data[1] | (static_cast<size_t>(data[2]) << 8), size - 3);
      const std::string tag = fuzz::input_file(data + 3, tag_bytes, "tag");
      const std::string csv = fuzz::input_file(data + 3 + tag_bytes, size - 3 - tag_bytes, "csv");
      const auto imu = read_tagged_imu_csv(csv, tag);
      for (size_t i = 1; i < imu.size(); ++i)
        fuzz::require(std::isfinite(imu[i].t_s) && imu[i].t_s > imu[i - 1].t_s, "tagged CSV: times not increasing");
    }
  } catch (const InputError&) {
  }
  return 0;
}
