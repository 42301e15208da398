#include "toolbox/diagnose/model_check.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "common/math/chi_square.hpp"
#include "toolbox/diagnose/statistics.hpp"

namespace ldv::diag {
namespace {

// Band for the mean of n_eff values each distributed as chi-square(dof)/dof*expected.
Band mean_band(double value, double expected, double dof, double n_eff, double confidence) {
  Band b;
  b.value = value;
  const double k = std::max(1.0, dof * n_eff);
  const double a = 0.5 * (1.0 - confidence);
  b.lo = expected * math::chi_square_quantile(a, k) / k;
  b.hi = expected * math::chi_square_quantile(1.0 - a, k) / k;
  return b;
}

std::vector<double> autocorrelation(const std::vector<Eigen::VectorXd>& x, int max_lag) {
  const int n = static_cast<int>(x.size());
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(x.empty() ? 0 : x.front().size());
  for (const auto& v : x) mean += v;
  mean /= std::max(1, n);
  std::vector<double> acf(max_lag + 1, 0.0);
  double var = 0.0;
  for (const auto& v : x) var += (v - mean).squaredNorm();
  if (var <= 0.0) return acf;
  for (int l = 0; l <= max_lag; ++l) {
    double c = 0.0;
    for (int i = 0; i + l < n; ++i) c += (x[i] - mean).dot(x[i + l] - mean);
    acf[l] = c / var;
  }
  return acf;
}

}  // namespace

bool SensorCheck::gate_drops_fixes() const { return rejected > std::max(1, count / 100); }

bool SensorCheck::ok() const { return !optimistic() && !gate_drops_fixes(); }

bool ModelCheck::gate_drops_fixes() const {
  return std::any_of(sensors.begin(), sensors.end(), [](const SensorCheck& s) { return s.gate_drops_fixes(); });
}

bool ModelCheck::consistent() const {
  for (const SensorCheck& s : sensors)
    if (!s.ok()) return false;
  return true;
}

const SensorCheck* ModelCheck::find(est::SensorName k) const {
  for (const SensorCheck& s : sensors)
    if (s.sensor == k) return &s;
  return nullptr;
}

double log_likelihood_term(const SensitivityRecord& r, double gate_probability) {
  const Eigen::LLT<Eigen::MatrixXd> llt(r.S);
  if (llt.info() != Eigen::Success) return 0.0;
  const double log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  const double gate = math::chi_square_quantile(gate_probability, static_cast<int>(r.innovation.size()));
  return -0.5 * (log_det + std::min(r.innovation.dot(llt.solve(r.innovation)), gate));
}

double log_likelihood(const std::vector<SensitivityRecord>& records, double gate_probability) {
  double ll = 0.0;
  for (const SensitivityRecord& r : records) ll += log_likelihood_term(r, gate_probability);
  return ll;
}

ModelCheck check_model(const FilterRun& run, const std::vector<Segment>& labels, double confidence) {
  ModelCheck mc;
  mc.loglik = log_likelihood(run.records, run.gate_probability);
  // Every sensor met, GNSS first; rows of a sensor are fixed (the first record's).
  std::vector<est::SensorName> names = {est::sensors::kGnssPosition, est::sensors::kGnssVelocity,
                                        est::sensors::kZeroVelocity};
  for (const auto& r : run.records)
    if (std::find(names.begin(), names.end(), r.sensor) == names.end()) names.push_back(r.sensor);
  for (const est::SensorName kind : names) {
    std::vector<const SensitivityRecord*> rs;
    for (const auto& r : run.records)
      if (r.sensor == kind && std::isfinite(r.nis) &&
          (rs.empty() || r.innovation.size() == rs.front()->innovation.size()))
        rs.push_back(&r);
    if (rs.size() < 10) continue;
    const int rows = static_cast<int>(rs.front()->innovation.size());
    SensorCheck sc;
    sc.sensor = kind;
    sc.count = static_cast<int>(rs.size());
    if (kind == est::sensors::kGnssPosition && rs.size() > 1)
      mc.measurement_interval_s = (rs.back()->t_s - rs.front()->t_s) / (rs.size() - 1);
    // NIS and per-axis NIS each capped at the chi-square gate of its rows (the run's own gate): a
    // rejected outlier weighs as much as a measurement just at the gate, not its NIS of 10^4 (one 2 m jump
    // among 1000 RTK fixes would otherwise lift the mean by ~10 and hide whether the model fits the rest),
    // while a filter that left the measurements still shows a mean near the gate. The RMS is over the
    // measurements used (rejections are counted apart); whiteness over all of them, in time order.
    const double nis_cap = math::chi_square_quantile(run.gate_probability, rows),
                 axis_cap = math::chi_square_quantile(run.gate_probability, 1);
    std::vector<Eigen::VectorXd> w;  // normalised innovations nu_i / sqrt(S_ii)
    double nis_sum = 0.0;
    Eigen::VectorXd axis_sum = Eigen::VectorXd::Zero(rows), sq = Eigen::VectorXd::Zero(rows);
    for (const auto* r : rs) {
      const Eigen::VectorXd sd = r->S.diagonal().cwiseSqrt();
      w.push_back(r->innovation.cwiseQuotient(sd));
      nis_sum += std::min(r->nis, nis_cap);
      axis_sum += w.back().cwiseAbs2().cwiseMin(axis_cap);
      if (!r->used) {
        ++sc.rejected;
        continue;
      }
      sq += r->innovation.cwiseAbs2();
    }
    const double n = sc.count;
    // Every measurement rejected: no RMS of the used ones (NaN), not a misleading 0.
    sc.rms = sc.rejected < sc.count ? Eigen::VectorXd((sq / (sc.count - sc.rejected)).cwiseSqrt())
                                    : Eigen::VectorXd::Constant(rows, NAN);
    // Whiteness: autocorrelation, Ljung-Box over h lags, integrated correlation time with Sokal's window.
    const int max_lag = std::min(sc.count / 4, 200);
    sc.autocorrelation = autocorrelation(w, max_lag);
    const int h = std::min(20, std::max(1, sc.count / 5));
    double q = 0.0;
    for (int l = 1; l <= h && l <= max_lag; ++l) q += sc.autocorrelation[l] * sc.autocorrelation[l] / (n - l);
    sc.ljung_box = n * (n + 2.0) * q;
    sc.ljung_box_lags = h;
    sc.ljung_box_p = chi_square_sf(sc.ljung_box, h);
    double tau = 1.0;
    for (int l = 1; l <= max_lag; ++l) {
      tau += 2.0 * sc.autocorrelation[l];
      if (l >= 5.0 * tau) break;
    }
    sc.correlation_time = std::clamp(tau, 1.0, n / 5.0);
    sc.effective_n = n / sc.correlation_time;
    sc.long_run_factor = sc.correlation_time;
    sc.mean_nis = mean_band(nis_sum / n, rows, rows, sc.effective_n, confidence);
    for (int i = 0; i < rows; ++i)
      sc.axis_nis.push_back(mean_band(axis_sum(i) / n, 1.0, 1.0, sc.effective_n, confidence));

    // Per manoeuvre segment.
    std::array<SegmentCheck, kSegmentCount> seg;
    std::array<Eigen::VectorXd, kSegmentCount> seg_sq;
    std::array<double, kSegmentCount> seg_nis{};
    for (int s = 0; s < kSegmentCount; ++s) {
      seg[s].segment = static_cast<Segment>(s);
      seg_sq[s] = Eigen::VectorXd::Zero(rows);
    }
    for (const auto* r : rs) {
      const int s = static_cast<int>(segment_at(run.epochs, labels, r->t_s));
      ++seg[s].count;
      seg_nis[s] += std::min(r->nis, nis_cap);
      if (!r->used) {
        ++seg[s].rejected;
        continue;
      }
      seg_sq[s] += r->innovation.cwiseAbs2();
    }
    for (int s = 0; s < kSegmentCount; ++s) {
      if (seg[s].count == 0) continue;
      const double ns = seg[s].count;
      seg[s].rms = (seg_sq[s] / std::max(1, seg[s].count - seg[s].rejected)).cwiseSqrt();
      seg[s].mean_nis = mean_band(seg_nis[s] / ns, rows, rows, std::max(1.0, ns / sc.correlation_time), confidence);
      sc.segments.push_back(seg[s]);
    }
    mc.sensors.push_back(std::move(sc));
  }
  return mc;
}

}  // namespace ldv::diag
