// The sign of the published innovation (NAV_INNOVATION, lcmtypes/nav_innovation_t.lcm): predicted minus
// measured, y = z_hat - z, NED. A vehicle at rest where the filter believes it is, and one GNSS fix displaced
// by a known NED vector d from that position: the fix measures z = r + d, the filter predicts z_hat = r, so
// y = -d. The message goes through fusion's code (FusionEngine, innovation_message) and LCM's encoding.
#include <gtest/gtest.h>

#include <cstdio>
#include <ldv_lcm/nav_innovation_t.hpp>
#include <vector>

#include "common/bus/bus.hpp"
#include "common/geo/earth_model.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "services/fusion/fusion_engine.hpp"
#include "services/fusion/nav_message.hpp"

using namespace ldv;

TEST(NavMessage, GivenAFixDisplacedFromTheFilter_ThenThePublishedInnovationIsPredictedMinusMeasured) {
  // Given fusion navigating a vehicle at rest, level, facing north, antenna at the IMU (no lever arm)
  est::FilterOptions fo;
  fo.zupt.enabled = false;  // only the GNSS update under test
  est::SessionOptions so;
  so.filter = fo;
  FusionEngine engine(so);
  const Geodetic r{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};
  const double t0 = 100000.0, dt = 0.01;
  est::NavState s;
  s.t_s = t0;
  s.pos = r;
  est::NavStd sd;
  sd.pos_ned_m = Vec3::Constant(2.0);  // the displacement is well inside the gate
  engine.filter().initialize(s, sd);
  // A perfect IMU at rest in NED axes senses -gravity and the Earth's rotation.
  ImuIncrement imu;
  imu.dt_s = dt;
  imu.dvel_b_mps = -earth::gravity_n(r.lat_rad, r.h_m) * dt;
  imu.dtheta_b_rad = earth::omega_ie_n(r.lat_rad) * dt;
  std::vector<FusionOutput> out;
  auto run_to = [&](double t_end) {
    while (engine.filter().state().t_s < t_end - 1e-9) {
      imu.t_s = engine.filter().state().t_s + dt;
      engine.on_imu(imu, 2300, 0.0, out);
    }
  };
  run_to(t0 + 1.0);
  ASSERT_LT(earth::ned_between(r, engine.filter().state().pos).norm(), 1e-3) << "the filter stays at rest";

  // When a fix 1 m north, 2 m west and 0.5 m down of it arrives and is applied
  const Vec3 d_ned_m(1.0, -2.0, 0.5);
  GnssFix fix;
  fix.t_s = t0 + 1.5;
  fix.pos = earth::offset_ned(r, d_ned_m);
  fix.pos_std_ned_m = Vec3::Constant(0.02);
  engine.on_gnss(fix, 2300, 0.0);
  run_to(t0 + 2.0);

  // Then the message fusion publishes for it says innovation = -d
  Bus bus("memq://");
  std::vector<ldv_lcm::nav_innovation_t> got;
  bus.subscribe<ldv_lcm::nav_innovation_t>(
      "NAV_INNOVATION", [&](const ldv_lcm::nav_innovation_t& m, const std::string&) { got.push_back(m); });
  int64_t seq = 0;
  for (const est::InnovationRecord& rec : engine.filter().take_innovations())
    ASSERT_TRUE(bus.publish("NAV_INNOVATION", innovation_message(rec, engine.week_time(rec.t_s), seq++)));
  while (bus.handle(0) > 0) {
  }
  ASSERT_EQ(got.size(), 1u);
  const ldv_lcm::nav_innovation_t& m = got[0];
  std::printf("fix displaced [%.2f %.2f %.2f] m NED: published innovation [%.6f %.6f %.6f] m\n", d_ned_m[0], d_ned_m[1],
              d_ned_m[2], m.innovation[0], m.innovation[1], m.innovation[2]);
  EXPECT_EQ(m.sensor, 1);  // GNSS position
  EXPECT_NEAR(m.gps_sow_s, fix.t_s, 1e-9);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.innovation[i], -d_ned_m[i], 1e-3) << "NED axis " << i;
  EXPECT_TRUE(m.accepted);
}
