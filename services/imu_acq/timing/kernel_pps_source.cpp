#include "services/imu_acq/timing/kernel_pps_source.hpp"

#include <fcntl.h>
#include <sys/timepps.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace ldv::timing {

std::optional<KernelPpsSource> KernelPpsSource::open(const std::string& device, std::string& error) {
  const int fd = ::open(device.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) {
    error = device + ": " + std::strerror(errno);
    return std::nullopt;
  }
  pps_handle_t handle{};
  if (time_pps_create(fd, &handle) < 0) {
    error = device + ": not a PPS device (" + std::strerror(errno) + ")";
    ::close(fd);
    return std::nullopt;
  }
  int capabilities = 0;
  if (time_pps_getcap(handle, &capabilities) < 0 || !(capabilities & PPS_CAPTUREASSERT) ||
      !(capabilities & PPS_CANWAIT)) {
    error = device + ": PPS device cannot capture and wait for assert edges";
    ::close(fd);
    return std::nullopt;
  }
  pps_params_t params{};
  if (time_pps_getparams(handle, &params) < 0) {
    error = device + ": time_pps_getparams: " + std::strerror(errno);
    ::close(fd);
    return std::nullopt;
  }
  params.mode |= PPS_CAPTUREASSERT;
  params.mode &= ~PPS_CAPTURECLEAR;
  if (time_pps_setparams(handle, &params) < 0) {
    error = device + ": time_pps_setparams: " + std::strerror(errno);
    ::close(fd);
    return std::nullopt;
  }
  return KernelPpsSource(fd);
}

KernelPpsSource::KernelPpsSource(KernelPpsSource&& other) noexcept
    : fd_(other.fd_), last_sequence_(other.last_sequence_) {
  other.fd_ = -1;
}

KernelPpsSource::~KernelPpsSource() {
  if (fd_ >= 0) time_pps_destroy(fd_);
}

std::optional<KernelPpsEvent> KernelPpsSource::fetch(double timeout_s, std::string& error) {
  error.clear();
  timespec timeout{};
  timeout.tv_sec = static_cast<time_t>(std::floor(timeout_s));
  timeout.tv_nsec = static_cast<long>((timeout_s - std::floor(timeout_s)) * 1e9);
  pps_info_t info{};
  if (time_pps_fetch(fd_, PPS_TSFMT_TSPEC, &info, &timeout) < 0) {
    if (errno != ETIMEDOUT) error = std::string("time_pps_fetch: ") + std::strerror(errno);
    return std::nullopt;
  }
  if (last_sequence_ && info.assert_sequence == *last_sequence_) return std::nullopt;  // no new edge
  last_sequence_ = info.assert_sequence;
  KernelPpsEvent e;
  e.sequence = info.assert_sequence;
  e.assert_time_ns = static_cast<std::int64_t>(info.assert_timestamp.tv_sec) * 1000000000LL +
                     info.assert_timestamp.tv_nsec;
  return e;
}

}  // namespace ldv::timing
