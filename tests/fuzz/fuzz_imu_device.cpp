// The IMU device protocols imu_acq reads (the time-stamp unit's frames and the 3DM-GX2's), any bytes in any
// chunking: never throws, and every sample handed out has finite increments.
#include <algorithm>
#include <memory>
#include <span>

#include "services/imu_acq/protocols/gx2_decoder.hpp"
#include "services/imu_acq/protocols/tsu_decoder.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  std::unique_ptr<imu::ImuDeviceDecoder> decoder;
  if (data[0] % 2 == 0)
    decoder = std::make_unique<imu::TsuDecoder>();
  else
    decoder = std::make_unique<imu::Gx2Decoder>();
  decoder->on_sample([](const imu::DeviceSample& s) {
    fuzz::require(s.dtheta_b_rad.allFinite() && s.dvel_b_mps.allFinite(), "a device sample not finite");
  });
  const size_t chunk = 1 + data[1] % 97;
  for (size_t at = 2; at < size; at += chunk)
    decoder->feed(std::span<const uint8_t>(data + at, std::min(chunk, size - at)));
  return 0;
}
