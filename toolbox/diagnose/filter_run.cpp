#include "toolbox/diagnose/filter_run.hpp"

#include <ctime>

#include "estimator/filter/nav_filter.hpp"

namespace ldv::diag {
namespace {
constexpr double kEpochPeriod_s = 0.1;

}  // namespace

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

FilterRun run_filter(const DiagnoseInputs& in, const est::FilterOptions& options, const CandidateSet* candidates) {
  const double cpu0 = process_cpu_seconds();
  FilterRun run;
  run.gate_probability = options.gate_probability;
  est::NavFilter filter(options);
  for (const auto& b : filter.layout().blocks()) run.effects.push_back(b.effect->name());
  std::unique_ptr<SensitivityObserver> observer;
  if (candidates) {
    observer = std::make_unique<SensitivityObserver>(filter, *candidates);
    filter.set_observer(observer.get());
  }
  est::RunCallbacks cb;
  double next_epoch_t = -1e300;
  cb.on_epoch = [&](const est::NavFilter& f) {
    if (observer) observer->on_imu_epoch();
    const est::NavState& s = f.state();
    if (s.t_s + 1e-9 < next_epoch_t) return;
    next_epoch_t = s.t_s + kEpochPeriod_s;
    const est::MechanizationStep& st = f.last_step();
    run.epochs.push_back({f.gnss_time_s(), s.pos, s.v_n_mps, s.rpy_rad(), st.omega_ib_b_rad_s, st.f_b_mps2, st.a_n_mps2,
                          (f.status() & est::kStatusGnssOutage) != 0});
  };
  if (!observer)
    cb.on_innovation = [&](const est::InnovationRecord& r) { run.records.push_back(SensitivityRecord::from(r)); };
  run.summary = est::run_navigation(in.imu, in.gnss, in.cfg, filter, cb, nullptr, &in.others);
  if (observer) run.records = observer->records();

  const Eigen::VectorXd sd = filter.covariance().diagonal().cwiseSqrt();
  for (const auto& b : filter.layout().blocks()) {
    EffectEstimate e;
    e.name = b.effect->name();
    e.state_names = b.effect->state_names();
    e.unit = b.effect->print_unit();
    e.value_si = filter.effect_state().segment(b.offset - est::kNavDim, b.dim);
    e.std_si = sd.segment(b.offset, b.dim);
    run.estimates.push_back(std::move(e));
  }
  run.cpu_s = process_cpu_seconds() - cpu0;
  return run;
}

}  // namespace ldv::diag
