#pragma once
// The fusion service's logic without the bus, so it is tested (and replayed by `ldv nav --lcm-log`)
// exactly as it runs live. It wraps the estimator's NavFilter (the same code as `ldv nav`):
//  - alignment: IMU samples wait in a queue until a GNSS fix beyond their epoch has arrived (or
//    align_wait_s of host time passed), so the aligner sees IMU and GNSS in the same order as the
//    offline run_navigation(), whatever the GNSS latency;
//  - navigation: late GNSS fixes go to NavFilter::add_gnss, which re-processes its IMU history, so
//    a fix is applied at its true epoch and the live result equals the offline one;
//  - warm start: after a restart, a recent saved state (attitude, velocity) plus the first GNSS fix
//    restart navigation at once instead of waiting for a static period. When the vehicle was and is
//    moving, the heading is carried through the restart gap by the change of the GNSS course over
//    ground (a land vehicle turns with its velocity), so a restart in the middle of a turn works.
#include <deque>
#include <optional>
#include <vector>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/ins/alignment.hpp"
#include "services/fusion/warm_start.hpp"

namespace ldv {

enum class FusionMode : int { kInitialising = 0, kAligning = 1, kAided = 2, kFreeInertial = 3 };

struct FusionOutput {
  int gps_week = 0;
  est::NavState state;
  est::NavStd std;
  std::uint32_t status = 0;
  FusionMode mode = FusionMode::kInitialising;
};

class FusionEngine {
 public:
  FusionEngine(const est::FilterOptions& filter_options, const est::AlignmentOptions& alignment_options,
               double align_wait_s = 1.0);

  // Optional: resume from a saved state (used until the first GNSS fix arrives).
  void set_warm_start(const WarmState& saved) { warm_ = saved; }

  // Appends the navigation outputs this sample produced (none while aligning).
  void on_imu(const ImuIncrement& imu, int gps_week, double arrival_s, std::vector<FusionOutput>& out);
  void on_gnss(const GnssFix& fix, double arrival_s);
  // Lets queued samples through when GNSS is silent (call periodically with the host time).
  void on_idle(double now_s, std::vector<FusionOutput>& out);

  bool navigating() const { return filter_.initialized(); }
  const est::NavFilter& filter() const { return filter_; }
  est::NavFilter& filter() { return filter_; }
  const std::string& initialisation() const { return initialisation_; }

 private:
  struct QueuedImu {
    ImuIncrement imu;
    int week;
    double arrival_s;
  };
  void drain_alignment_queue(double now_s, std::vector<FusionOutput>& out);
  void start_navigation(const est::NavState& s, const est::NavStd& sd, const std::string& how);
  bool try_warm_start(const ImuIncrement& imu);
  void navigate(const ImuIncrement& imu, int week, std::vector<FusionOutput>& out);

  est::NavFilter filter_;
  est::Aligner aligner_;
  double speed_min_mps_;     // course over ground usable above this (AlignmentOptions)
  double cog_yaw_std_rad_;   // heading uncertainty from the course over ground
  double align_wait_s_;
  std::deque<QueuedImu> imu_queue_;
  std::deque<GnssFix> gnss_queue_;  // fixes not yet given to the aligner
  double latest_gnss_t_s_ = -1e300;
  std::optional<WarmState> warm_;
  std::optional<GnssFix> warm_fix_;
  std::string initialisation_;
};

}  // namespace ldv
