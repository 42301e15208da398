#pragma once
// Replays a recorded stream at the pace it was recorded: the first epoch is pinned to the host
// clock, and bytes are held back while the data's epochs run ahead of the host clock (scaled by
// speed_factor: 1 real time, 10 ten times faster; 0 disables pacing).
#include <optional>

namespace ldv::io {

class RealTimePacer {
 public:
  explicit RealTimePacer(double speed_factor) : speed_factor_(speed_factor) {}

  // A data epoch [s, any continuous time scale] was just decoded at host time now_s.
  void on_epoch(double epoch_s, double now_s) {
    if (!first_epoch_s_) {
      first_epoch_s_ = epoch_s;
      first_host_s_ = now_s;
    }
    latest_epoch_s_ = epoch_s;
  }
  // Seconds to wait before reading more (0 when the data is not ahead of the clock).
  double hold_s(double now_s) const {
    if (speed_factor_ <= 0.0 || !first_epoch_s_) return 0.0;
    const double due_host_s = first_host_s_ + (latest_epoch_s_ - *first_epoch_s_) / speed_factor_;
    return due_host_s > now_s ? due_host_s - now_s : 0.0;
  }

 private:
  double speed_factor_;
  std::optional<double> first_epoch_s_;
  double first_host_s_ = 0.0, latest_epoch_s_ = 0.0;
};

}  // namespace ldv::io
