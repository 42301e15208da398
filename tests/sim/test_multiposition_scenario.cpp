// The multi-position calibration session (`ldv sim --scenario multiposition`, sim/builtin_scenarios.cpp) against
// its specification written out here: 18 static poses (30 s, then 10 s each) with 3 s rotations between them, the
// body axis that points down in each pose, and the attitude of each pose as ZYX Euler angles. Physics from
// GeographicLib and the WGS84 Earth rate directly: in every pose the body stands still and senses -gravity along
// the specified direction (within 6 deg of the named axis) and Earth rate; the gyro increments of every rotation,
// integrated, turn pose k into pose k+1.
#include <gtest/gtest.h>

#include <GeographicLib/NormalGravity.hpp>
#include <algorithm>
#include <cmath>

#include "sim/scenario.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

namespace {
constexpr double kPoseOmegaEarth = 7.2921151467e-5;  // WGS84 [rad/s]
constexpr double kRate = 100.0;                  // IMU rate of these tests [Hz]
constexpr double kFirstS = 30.0, kPoseS = 10.0, kTurnS = 3.0;
constexpr int kPoses = 18;

Vec3 pose_normal_gravity_ned(const Geodetic& p) {
  double gn = 0, gu = 0;
  GeographicLib::NormalGravity::WGS84().Gravity(p.lat_rad * kRadToDeg, p.h_m, gn, gu);
  return {gn, 0.0, -gu};
}
Vec3 pose_earth_rate_ned(double lat) {
  return {kPoseOmegaEarth * std::cos(lat), 0.0, -kPoseOmegaEarth * std::sin(lat)};
}

// The specification: per pose the ZYX Euler angles [deg] (2-5 deg off the nominal table pose, on purpose) and the
// body direction that nominally points down.
struct Spec {
  double roll, pitch, yaw;
  Vec3 down;
};
const double kS3 = 1.0 / std::sqrt(3.0), kS2 = 1.0 / std::sqrt(2.0);
const Spec kSpec[kPoses] = {
    {2, -3, 0, {0, 0, 1}},              // z down (level)
    {87, 2, 180, {0, 1, 0}},            // y down
    {183, -2, 180, {0, 0, -1}},         // z up
    {133, 38, 180, {-kS3, kS3, -kS3}},  // corners ...
    {138, -37, 90, {kS3, kS3, -kS3}},
    {140, -86, -90, {1, 0, 0}},  // x down
    {42, -33, 180, {kS3, kS3, kS3}},
    {47, 32, 0, {-kS3, kS3, kS3}},
    {40, 86, -90, {-1, 0, 0}},  // x up
    {-47, 37, 180, {-kS3, -kS3, kS3}},
    {-42, -37, 0, {kS3, -kS3, kS3}},
    {-92, 3, 180, {0, -1, 0}},  // y up
    {-133, -38, -90, {kS3, -kS3, -kS3}},
    {-138, 37, 0, {-kS3, -kS3, -kS3}},
    {-177, -42, 0, {kS2, 0, -kS2}},  // edges ...
    {-92, 43, 0, {-kS2, -kS2, 0}},
    {2, 48, 180, {-kS2, 0, kS2}},
    {42, 2, 0, {0, kS2, kS2}},
};

Mat3 spec_C_b_n(int k) { return C_b_n_from_euler(Vec3(kSpec[k].roll, kSpec[k].pitch, kSpec[k].yaw) * kDegToRad); }
// Pose k (0-based) stands still over [begin, end) seconds from the run start.
double pose_begin_s(int k) { return k == 0 ? 0.0 : kFirstS + k * kTurnS + (k - 1) * kPoseS; }
double pose_end_s(int k) { return k == 0 ? kFirstS : pose_begin_s(k) + kPoseS; }
size_t sample(double t_s) { return static_cast<size_t>(std::llround(t_s * kRate)); }
// The angle of the rotation from a to b (through the quaternion: exact for small angles too).
double angle_between(const Mat3& a, const Mat3& b) { return rotvec_from_quat(Quat(Mat3(a.transpose() * b))).norm(); }
}  // namespace

// Outside the anonymous namespace: the tests derive from it (GCC warns of a test class whose base has internal
// linkage when the file is compiled inside a unity batch).
class MultipositionScenario : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // The whole session (30 + 17 x 13 = 251 s) and 1 s more: the last pose holds.
    run_ = new SimResult(simulate(perfect_request("multiposition", 252.0, kRate)));
  }
  static void TearDownTestSuite() {
    delete run_;
    run_ = nullptr;
  }
  static SimResult* run_;
};
SimResult* MultipositionScenario::run_ = nullptr;

TEST_F(MultipositionScenario, TheNamesResolveAndTheDefaultSessionIsEighteenPoses) {
  const auto names = builtin_scenario_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "multiposition"), names.end());
  auto poses_in = [](const std::string& name) {
    const Scenario s = load_scenario(name);
    int n = 0;
    for (const Segment& g : s.segments) n += g.type == "static";
    return n;
  };
  EXPECT_EQ(poses_in("multiposition"), 18);
  EXPECT_EQ(poses_in("multiposition:13"), 13);
  EXPECT_EQ(poses_in("multiposition:36:60"), 36);
  // The schedule: 30 s first pose, 3 s rotations, 10 s poses; POSE_S = 60 lengthens the first pose too.
  EXPECT_NEAR(compile_scenario(load_scenario("multiposition"), 1e5).scheduled_s, 251.0, 1e-9);
  EXPECT_NEAR(compile_scenario(load_scenario("multiposition:36:60"), 1e5).scheduled_s, 60.0 + 35 * 63.0, 1e-9);
  for (const char* bad : {"multiposition:0", "multiposition:37", "multiposition:x", "multiposition:13:0",
                          "multiposition:13:", "multiposition:2.5", "multipositions"}) {
    EXPECT_TRUE(builtin_scenario_yaml(bad).empty()) << bad;
    EXPECT_NE(input_error_of([&] { load_scenario(bad); }), "") << bad;
  }
}

TEST_F(MultipositionScenario, EveryPoseStandsStillAndSensesGravityAlongItsNamedAxisAndEarthRate) {
  const SimResult& r = *run_;
  ASSERT_EQ(r.imu.size(), sample(252.0));
  const Geodetic p0 = r.truth.front().pos;
  const Vec3 g_n = pose_normal_gravity_ned(p0), w_ie_n = pose_earth_rate_ned(p0.lat_rad);
  for (int k = 0; k < kPoses; ++k) {
    const Mat3 C = spec_C_b_n(k);
    // The attitude is the specified one throughout the pose (truth rpy through its own rotation matrix).
    for (size_t i = sample(pose_begin_s(k)); i <= sample(pose_end_s(k)); ++i) {
      const TruthSample& t = r.truth[i];
      ASSERT_LT(angle_between(C_b_n_from_euler(t.rpy_rad), C), 1e-12) << "pose " << k + 1 << " sample " << i;
      ASSERT_LT(t.vel_n_mps.norm(), 1e-12) << "pose " << k + 1;
      ASSERT_LT(exact_ned(p0, t.pos).norm(), 1e-9) << "pose " << k + 1;
    }
    // Every increment inside the pose is the static closed form: -gravity and Earth rate in body axes.
    Vec3 f_sum = Vec3::Zero();
    for (size_t i = sample(pose_begin_s(k)); i < sample(pose_end_s(k)); ++i) {
      const ImuIncrement& s = r.imu[i];
      ASSERT_LT((s.dvel_b_mps - (-C.transpose() * g_n * s.dt_s)).norm(), 1e-12) << "pose " << k + 1;    // of 0.098 m/s
      ASSERT_LT((s.dtheta_b_rad - C.transpose() * w_ie_n * s.dt_s).norm(), 1e-17) << "pose " << k + 1;  // of 7e-7 rad
      f_sum += s.dvel_b_mps;
    }
    // Gravity points along the specified direction (the third row of C_b_n: the body's down): the sensed specific
    // force is -g along it, to the deflection of normal gravity from the ellipsoid normal (< 1e-5 rad at 100 m),
    // and within 6 deg of the nominal axis, corner or edge the pose is named after.
    const Vec3 f = f_sum / (pose_end_s(k) - pose_begin_s(k));
    const Vec3 down = C.row(2).transpose();
    EXPECT_NEAR(f.norm(), g_n.norm(), 1e-10) << "pose " << k + 1;
    EXPECT_LT(std::acos(std::clamp(-f.normalized().dot(down), -1.0, 1.0)), 1e-5) << "pose " << k + 1;
    const double off_nominal = std::acos(std::clamp(-f.normalized().dot(kSpec[k].down.normalized()), -1.0, 1.0));
    EXPECT_LT(off_nominal, 6.0 * kDegToRad) << "pose " << k + 1 << ": f = " << f.transpose();
    EXPECT_GT(off_nominal, 2.0 * kDegToRad) << "pose " << k + 1;
    // No two components of the gravity direction have the same magnitude (ldv calib static's tangent basis).
    Vec3 m = f.normalized().cwiseAbs();
    std::sort(m.data(), m.data() + 3);
    EXPECT_GT(m[1] - m[0], 0.008) << "pose " << k + 1;
  }
}

TEST_F(MultipositionScenario, TheGyroIncrementsTurnEachPoseIntoTheNextAndEveryTurnTiltsGravity) {
  const SimResult& r = *run_;
  const Geodetic p0 = r.truth.front().pos;
  const Vec3 w_ie_n = pose_earth_rate_ned(p0.lat_rad);
  for (int k = 0; k + 1 < kPoses; ++k) {
    // Strapdown from the middle of pose k to the middle of pose k+1 on the sensed increments (two-sample coning
    // correction); the navigation frame turns with the Earth meanwhile: C(T) = Exp(-w_ie T) C(0) R_b.
    const size_t i0 = sample(0.5 * (pose_begin_s(k) + pose_end_s(k)));
    const size_t i1 = sample(0.5 * (pose_begin_s(k + 1) + pose_end_s(k + 1)));
    Quat q = Quat::Identity();
    Vec3 previous = Vec3::Zero();
    for (size_t i = i0; i < i1; ++i) {
      const Vec3& d = r.imu[i].dtheta_b_rad;
      q = q * quat_from_rotvec(d + previous.cross(d) / 12.0);
      previous = d;
    }
    const double T = static_cast<double>(i1 - i0) / kRate;
    const Mat3 predicted = quat_from_rotvec(-w_ie_n * T).toRotationMatrix() * spec_C_b_n(k) * q.toRotationMatrix();
    // (1e-6 rad: the two-sample algorithm at 100 Hz on turns of up to 132 deg/s; a wrong pose is off by degrees)
    EXPECT_LT(angle_between(predicted, spec_C_b_n(k + 1)), 1e-6) << "rotation " << k + 1 << " -> " << k + 2;
    // The rotation moves gravity by 48 deg or more (a condition for the gyro rotation method), and turns by it.
    const Vec3 d0 = spec_C_b_n(k).row(2).transpose(), d1 = spec_C_b_n(k + 1).row(2).transpose();
    const double tilt = std::acos(std::clamp(d0.dot(d1), -1.0, 1.0));
    EXPECT_GE(tilt, 48.0 * kDegToRad) << "rotation " << k + 1 << " -> " << k + 2;
    EXPECT_GE(angle_between(spec_C_b_n(k), spec_C_b_n(k + 1)), tilt - 1e-9);
    // Nothing moves but the attitude: the body stays at the same point.
    for (size_t i = i0; i <= i1; ++i) ASSERT_LT(exact_ned(p0, r.truth[i].pos).norm(), 1e-9);
  }
}

TEST_F(MultipositionScenario, EarthRateAveragesOutOfTheMeanStaticGyroReading) {
  // The rotation method reports the mean static gyro reading over the poses as the bias: the yaws are chosen so
  // that Earth rate contributes < 0.064 of its magnitude (|sum C_b_n| = 1.15 of 18 by the design).
  const SimResult& r = *run_;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < kPoses; ++k) {
    Vec3 sum = Vec3::Zero();
    for (size_t i = sample(pose_begin_s(k)); i < sample(pose_end_s(k)); ++i) sum += r.imu[i].dtheta_b_rad;
    mean += sum / (pose_end_s(k) - pose_begin_s(k)) / kPoses;
  }
  EXPECT_LT(mean.norm(), 0.064 * kPoseOmegaEarth) << mean.transpose() / kPoseOmegaEarth;
}

TEST(MultipositionPoseSegment, TurnsTheHeadingTheShortWayAndRampsRollAndPitchAsGiven) {
  const std::string file = write_text("pose.yaml", R"(name: pose
start: {yaw_deg: 170}
segments:
  - {type: static, duration_s: 1}
  - {type: pose, yaw_deg: -170, roll_deg: -120, duration_s: 2}
  - {type: static, duration_s: 1}
  - {type: pose, pitch_deg: -90, duration_s: 2}
  - {type: static, duration_s: 1}
)");
  const SimResult r = simulate(perfect_request(file, 7.0, kRate));
  // 170 -> -170 is +20 deg through 180 (not -340): the heading only ever increases.
  for (size_t i = sample(1.0); i < sample(3.0); ++i)
    ASSERT_GE(wrap_pi(r.truth[i + 1].rpy_rad.z() - r.truth[i].rpy_rad.z()), 0.0) << i;
  const Mat3 after_first = C_b_n_from_euler(Vec3(-120, 0, -170) * kDegToRad);
  EXPECT_LT(angle_between(C_b_n_from_euler(r.truth[sample(3.5)].rpy_rad), after_first), 1e-12);
  // Roll ramps from 0 to -120 as given; pitch then reaches -90 (body x down) with the roll kept.
  EXPECT_NEAR(r.truth[sample(3.5)].rpy_rad.x(), -120 * kDegToRad, 1e-12);
  const Vec3 f = r.truth[sample(6.5)].f_b_mps2;
  EXPECT_LT(std::acos(std::clamp(-f.normalized().x(), -1.0, 1.0)), 1e-5) << f.transpose();
}

TEST(MultipositionPoseSegment, BadPosesAreInputErrorsNamingTheField) {
  auto error_of = [](const std::string& segment) {
    const std::string file =
        write_text("bad_pose.yaml", "name: bad\nsegments:\n  - {type: static, duration_s: 1}\n  - " + segment + "\n");
    return input_error_of([&] { compile_scenario(load_scenario(file), 10.0); });
  };
  EXPECT_NE(error_of("{type: pose, duration_s: 2}").find("roll_deg"), std::string::npos);
  EXPECT_NE(error_of("{type: pose, pitch_deg: 91, duration_s: 2}").find("pitch_deg"), std::string::npos);
  EXPECT_NE(error_of("{type: pose, roll_deg: 30, duration_s: 0}").find("duration_s"), std::string::npos);
  EXPECT_NE(error_of("{type: pose, roll_deg: 30, speed_mps: 1, duration_s: 2}").find("speed_mps"), std::string::npos);
  // Turned standing only.
  const std::string moving = write_text("moving_pose.yaml", R"(name: moving
segments:
  - {type: accelerate, to_speed_mps: 5, duration_s: 2}
  - {type: pose, roll_deg: 30, duration_s: 2}
)");
  EXPECT_NE(input_error_of([&] { compile_scenario(load_scenario(moving), 10.0); }).find("standing"), std::string::npos);
}
