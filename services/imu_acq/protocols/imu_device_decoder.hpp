#pragma once
// What every IMU device protocol decoder gives imu_acq: samples with the device counter latched
// at the sample instant and their increments in SI units, and PPS latches (the same counter
// latched at the PPS edge) when the device has a PPS input. Decoders are incremental
// (feed(bytes) in any chunking) and never throw on input: bad frames are counted and skipped.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include "common/math/rotation.hpp"

namespace ldv::imu {

struct DeviceSample {
  std::uint64_t counter = 0;  // raw latch, counter_bits() wide
  Vec3 dtheta_b_rad = Vec3::Zero();  // over (previous sample, this sample], device axes
  Vec3 dvel_b_mps = Vec3::Zero();
  bool device_error = false;  // over-range or the device's own error flag
};

struct DevicePpsLatch {
  std::uint64_t counter = 0;
};

struct DecoderCounters {
  std::uint64_t frames = 0;          // good frames
  std::uint64_t bad_checksum = 0;    // CRC / checksum failures
  std::uint64_t skipped_bytes = 0;   // bytes outside frames
  std::uint64_t lost_samples = 0;    // from the device's sample sequence numbers
};

class ImuDeviceDecoder {
 public:
  using SampleHandler = std::function<void(const DeviceSample&)>;
  using PpsHandler = std::function<void(const DevicePpsLatch&)>;

  virtual ~ImuDeviceDecoder() = default;
  virtual void feed(std::span<const std::uint8_t> bytes) = 0;
  virtual int counter_bits() const = 0;
  virtual double nominal_counter_hz() const = 0;
  virtual const DecoderCounters& counters() const = 0;

  void on_sample(SampleHandler h) { on_sample_ = std::move(h); }
  void on_pps(PpsHandler h) { on_pps_ = std::move(h); }

 protected:
  SampleHandler on_sample_;
  PpsHandler on_pps_;
};

}  // namespace ldv::imu
