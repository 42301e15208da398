#include "estimator/calibrate/imu_latency_window.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <system_error>

namespace ldv::est {
namespace {
// Kept beyond the window: a search starts at a fix older than the newest IMU sample (the IMU runs ahead).
constexpr double kKeptBeyondWindow_s = 10.0;
}  // namespace

void ImuLatencyWindow::add_imu(const ImuIncrement& raw) {
  if (!std::isfinite(raw.t_s) || (!imu_.empty() && raw.t_s <= imu_.back().t_s)) return;
  imu_.push_back(raw);
  while (imu_.front().t_s < raw.t_s - o_.window_s - kKeptBeyondWindow_s) imu_.pop_front();
  if (pending_ && raw.t_s >= pending_->window_end_s + kApplyAfter_s) {
    ImuLatencyEstimate e;  // invalid unless the search returns
    try {
      e = pending_->estimate.get();  // waits only if the worker is slower than 2 s of data
    } catch (const std::exception&) {
      // A search that failed (out of memory) decides nothing; a service never stops for it.
    }
    const double window_end_s = pending_->window_end_s;
    pending_.reset();
    decide(e, window_end_s, raw.t_s);
  }
}

void ImuLatencyWindow::add_gnss(const GnssFix& fix) {
  if (!std::isfinite(fix.t_s)) return;
  // In time order (a live stream can deliver a late solution after a newer one); a repeated epoch once.
  auto at = std::lower_bound(gnss_.begin(), gnss_.end(), fix.t_s, [](const GnssFix& f, double t) { return f.t_s < t; });
  if (at != gnss_.end() && at->t_s == fix.t_s) return;
  gnss_.insert(at, fix);
  while (gnss_.front().t_s < gnss_.back().t_s - o_.window_s - kKeptBeyondWindow_s) gnss_.pop_front();
  if (next_search_t_s_ == -1e300) next_search_t_s_ = fix.t_s + o_.every_s;
  if (fix.t_s < next_search_t_s_ || pending_) return;
  next_search_t_s_ = fix.t_s + o_.every_s;
  start_search(fix.t_s);
}

void ImuLatencyWindow::start_search(double window_end_s) {
  // The data of [end - window, end] only, by their stamps: what has arrived beyond the end depends on the
  // transport, and a replayed log must decide as the live service did.
  std::vector<ImuIncrement> imu;
  for (const ImuIncrement& s : imu_)
    if (s.t_s >= window_end_s - o_.window_s && s.t_s <= window_end_s) imu.push_back(s);
  std::vector<GnssFix> gnss;
  for (const GnssFix& f : gnss_)
    if (f.t_s >= window_end_s - o_.window_s && f.t_s <= window_end_s) gnss.push_back(f);
  auto task = [imu = std::move(imu), gnss = std::move(gnss), search = o_.search] {
    return estimate_imu_latency(imu, gnss, search);
  };
  try {
    pending_ = Pending{window_end_s, std::async(std::launch::async, task)};
  } catch (const std::system_error&) {  // no thread to be had (a process at its limit): run it when it is due
    pending_ = Pending{window_end_s, std::async(std::launch::deferred, task)};
  }
}

void ImuLatencyWindow::decide(const ImuLatencyEstimate& e, double window_end_s, double imu_t_s) {
  last_ = e;
  ++estimates_;
  if (!e.valid || !(e.sigma_s < 0.02)) return;  // too few turns in the window, or too loosely known
  const double target_s = e.significant() ? e.lag_s : 0.0;
  const double change_s = std::abs(target_s - lag_s_);
  // A lag found at the first few turns (sigma near 20 ms) is refined as more turns come in: taken again
  // when known twice as well as the one in use.
  const bool refined =
      e.significant() && !decisions_.empty() && e.sigma_s < 0.5 * decisions_.back().sigma_s && change_s > 0.001;
  if (change_s <= std::max(3.0 * e.sigma_s, 0.005) && !refined) return;
  lag_s_ = target_s;
  decisions_.push_back({window_end_s, imu_t_s, lag_s_, e.sigma_s, e.turning_intervals});
}

}  // namespace ldv::est
