#include "estimator/update/gnss_position.hpp"

#include "common/formats/gnss_solution_checks.hpp"
#include "common/geo/earth_model.hpp"

namespace ldv::est {

Measurement gnss_position_measurement(const NavState& s, const LinearizationPoint& lp, const StateLayout& layout,
                                      const GnssFix& fix) {
  Measurement m(sensors::kGnssPosition, 3, layout.size());
  m.gnss = true;
  m.step_block = kPos;
  m.gnss_class = fix.quality == GnssQuality::kFixed || fix.quality == GnssQuality::kPpp ? 0
                 : fix.quality == GnssQuality::kFloat                                   ? 1
                                                                                        : 2;
  const Vec3 lever_n = lp.C_b_n * lp.lever_arm_b_m;
  const Geodetic ant = earth::offset_ned(s.pos, lever_n);
  m.y = earth::ned_between(fix.pos, ant) + lp.gnss_position_bias_n_m;
  m.H.middleCols<3>(kPos).setIdentity();
  // C_hat l = (I - [phi x]) C l  =>  d/dphi = [(C l) x]
  m.H.middleCols<3>(kAtt) = skew(lever_n);
  add_effect_columns(layout, lp, m);
  m.R = Mat3(fix.pos_std_ned_m.cwiseAbs().cwiseMax(gnss::kMinCredibleGnssPositionStd_m).cwiseAbs2().asDiagonal());
  adjust_effect_noise(layout, m);
  return m;
}

}  // namespace ldv::est
