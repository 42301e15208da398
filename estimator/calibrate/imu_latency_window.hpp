#pragma once
// The IMU latency found live: the same estimate as over a whole file (imu_latency.hpp), run over a sliding
// window of the most recent data. A live service has no file to search before it starts; the latency shows
// only once the vehicle has turned, so it is decided while navigating and changed when the data say so
// (a USB or serial buffer whose fill changes after a reconnect).
//
// The window keeps the IMU increments on their own (raw) stamps and the GNSS fixes, so every estimate is of
// the whole lag, not of a residual on data re-timed part-way through. A lag is adopted when the estimate is
// significant by the file estimate's rule (beyond 3 sigma, beyond what a forward lever arm explains, known
// to better than 20 ms) and differs from the one in use by more than 3 sigma and 5 ms, or is known twice as
// well (a lag found at the first turns is refined); a lag in use is dropped when a window known to better
// than 20 ms says it is gone.
//
// Real time: the search (tens of ms over 5 min at 200 Hz) runs on a worker thread, off the fusion service's
// latency path. Its answer is taken at a point fixed in data time (the first IMU sample kApplyAfter_s past the
// window's end), waiting for it there if it is not ready, so a replayed log decides exactly as the service did.
#include <deque>
#include <future>
#include <optional>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "estimator/calibrate/imu_latency.hpp"

namespace ldv::est {

struct ImuLatencyWindowOptions {
  double window_s = 300.0;  // data the estimate looks at
  double every_s = 20.0;    // re-estimated this often (GNSS time)
  ImuLatencyOptions search;
};

struct ImuLatencyDecision {
  double window_end_s = 0.0;  // the estimate is over [window_end - window_s, window_end] (GNSS time)
  double from_imu_t_s = 0.0;  // raw stamp of the first IMU sample re-timed by it
  double lag_s = 0.0;         // taken out of every later IMU stamp (0: none)
  double sigma_s = 0.0;       // of the window's estimate
  int turning_intervals = 0;
};

class ImuLatencyWindow {
 public:
  static constexpr double kApplyAfter_s = 2.0;

  // A search still running at destruction is waited for by its future (it works on copies of the data).
  explicit ImuLatencyWindow(ImuLatencyWindowOptions options = {}) : o_(options) {}

  // A sample on its raw stamp, before the lag is taken out of it: lag_s() is then the one for this sample.
  void add_imu(const ImuIncrement& raw);
  // A fix on GNSS time; every every_s, the search over the window ending at this fix is started.
  void add_gnss(const GnssFix& fix);

  double lag_s() const { return lag_s_; }  // subtract from the raw IMU stamps
  const std::vector<ImuLatencyDecision>& decisions() const { return decisions_; }
  const ImuLatencyEstimate& last_estimate() const { return last_; }
  int estimates() const { return estimates_; }

 private:
  struct Pending {
    double window_end_s;
    std::future<ImuLatencyEstimate> estimate;
  };
  void start_search(double window_end_s);
  void decide(const ImuLatencyEstimate& e, double window_end_s, double imu_t_s);

  ImuLatencyWindowOptions o_;
  std::deque<ImuIncrement> imu_;
  std::deque<GnssFix> gnss_;
  double next_search_t_s_ = -1e300;
  std::optional<Pending> pending_;
  double lag_s_ = 0.0;
  ImuLatencyEstimate last_;
  int estimates_ = 0;
  std::vector<ImuLatencyDecision> decisions_;
};

}  // namespace ldv::est
