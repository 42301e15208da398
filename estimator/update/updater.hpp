#pragma once
// An aid that looks at the IMU stream itself (ZUPT, ZARU, the non-holonomic constraint): after every IMU
// sample it may emit measurements to apply at once. Updaters live in the filter's state (they are copied
// into its snapshots, so a rewind replays them exactly): keep their own state small.
//
// A new aid: one file with an Updater subclass and its factory, and one line in updater_list.hpp
// (estimator/README.md, "Adding an aid").
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "estimator/filter/status.hpp"
#include "estimator/ins/mechanization.hpp"
#include "estimator/options.hpp"
#include "estimator/update/measurement.hpp"
#include "estimator/update/zupt.hpp"

namespace ldv::est {

// The filter as an aid sees it after an IMU sample.
struct AidContext {
  const NavState& nav;
  const LinearizationPoint& lp;  // valid in measure() only (due() is asked before it is taken)
  const StateLayout& layout;
  const FilterOptions& options;
  const Eigen::MatrixXd& P;        // current covariance (flushed to this epoch)
  const StaticDetector& detector;  // standstill detection over options.zupt.window_s
  const Vec3& f_n_smooth_mps2;     // specific force in n, low-passed (window / 4)
  bool gnss_recent;                // a GNSS measurement was used within the last second
  double gyro_noise_scale;         // factor on the configured gyro white-noise PSD (installed, adapted)
  FaultCounters& faults;
};

class Updater {
 public:
  virtual ~Updater() = default;
  virtual const char* name() const = 0;
  virtual std::unique_ptr<Updater> clone() const = 0;
  // Whether the aid wants to measure now. Cheap: ctx.P is the covariance at the last covariance epoch
  // (up to options.cov_period_s old). When it does, the filter brings the covariance to this epoch and
  // calls measure(), which may still decide to emit nothing.
  virtual bool due(const AidContext& ctx) const = 0;
  virtual void measure(const AidContext& ctx, std::vector<Measurement>& out) = 0;
};

// A copyable owner of an updater (copies clone it): what the filter's state holds.
class UpdaterSlot {
 public:
  explicit UpdaterSlot(std::unique_ptr<Updater> u) : u_(std::move(u)) {}
  UpdaterSlot(const UpdaterSlot& o) : u_(o.u_->clone()) {}
  UpdaterSlot& operator=(const UpdaterSlot& o) {
    if (this != &o) u_ = o.u_->clone();
    return *this;
  }
  UpdaterSlot(UpdaterSlot&&) = default;
  UpdaterSlot& operator=(UpdaterSlot&&) = default;
  Updater* operator->() const { return u_.get(); }

 private:
  std::unique_ptr<Updater> u_;
};

// The aids by name (updater_list.hpp): "zupt", "zaru", "nhc". Throws std::invalid_argument naming an
// unknown one and the known ones.
std::unique_ptr<Updater> make_updater(const std::string& name, const FilterOptions& options);
// What --aid / ldv.aids accept: the registered updaters but zupt (on unless ldv.zupt: false), and "odometer".
std::vector<std::string> aid_names();
bool is_aid_name(const std::string& name);
std::string aid_name_list();  // "nhc, zaru, odometer"
// The updaters a filter with these options runs: zupt when options.zupt.enabled, then options.aids.enabled
// (except "odometer", which is an external sensor: estimator/update/odometer.hpp).
std::vector<UpdaterSlot> make_updaters(const FilterOptions& options);

}  // namespace ldv::est
