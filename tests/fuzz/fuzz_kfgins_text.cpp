// KF-GINS text readers (imu.txt, gnss.txt, .nav) and the odometer text: whatever the bytes, an InputError
// naming the file or records whose times strictly increase and whose values are finite.
#include <cmath>

#include "common/formats/kfgins_files.hpp"
#include "common/formats/odometer_text.hpp"
#include "common/io/input_error.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fuzz::input_file(data + 1, size - 1);
  try {
    switch (data[0] % 4) {
      case 0: {
        const auto imu = read_kfgins_imu(path);
        for (size_t i = 0; i < imu.size(); ++i) {
          fuzz::require(std::isfinite(imu[i].t_s) && imu[i].dtheta_b_rad.allFinite() && imu[i].dvel_b_mps.allFinite(),
                        "imu.txt: a sample not finite");
          if (i > 0) fuzz::require(imu[i].t_s > imu[i - 1].t_s, "imu.txt: times not increasing");
        }
        break;
      }
      case 1: {
        const auto gnss = read_kfgins_gnss(path);
        for (size_t i = 0; i < gnss.size(); ++i) {
          fuzz::require(gnss[i].pos_std_ned_m.allFinite() && (gnss[i].pos_std_ned_m.array() > 0).all(),
                        "gnss.txt: a std not positive and finite");
          if (i > 0) fuzz::require(gnss[i].t_s > gnss[i - 1].t_s, "gnss.txt: times not increasing");
        }
        break;
      }
      case 2:
        read_nav(path);
        break;
      case 3: {
        const auto odo = read_odometer_text(path);
        for (size_t i = 1; i < odo.size(); ++i)
          fuzz::require(odo[i].t_s > odo[i - 1].t_s, "odo.txt: times not increasing");
        break;
      }
    }
  } catch (const InputError&) {
  }
  return 0;
}
