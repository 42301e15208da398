// The named grades (hg1700, hg1900, 3dm-gx2 and their -paper aliases) against the paper's printed tables (read
// from ../shared/data/paper/geo_ldv_tables.yaml at run time, never retyped here): every term per axis, absent
// terms absent, Table 3's datasheet constants. The unit conversions below are written independently of
// sim/imu_grade.cpp, so a typo in a value or a factor there fails. The -typical stand-ins exist beside them. Then
// the grade YAML file: the example, a round trip of every built-in, and bad input.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

namespace {
const double kPiDeg = 3.14159265358979323846 / 180.0;

YAML::Node paper() {
  static const YAML::Node root = YAML::LoadFile(std::string(LDV_SHARED_DATA_DIR) + "/paper/geo_ldv_tables.yaml");
  return root;
}

// Per-axis X, Y, Z of a printed row (the 4th column is the paper's average); null -> 0 (absent).
Vec3 row(const char* table, const char* key, double to_si) {
  const YAML::Node n = paper()[table][key];
  EXPECT_TRUE(n.IsSequence()) << table << "." << key;
  Vec3 v = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    if (!n[i].IsNull()) v[i] = n[i].as<double>() * to_si;
  return v;
}
double datasheet(const char* imu, const char* key, double to_si) {
  return paper()["table3_datasheets"][imu][key].as<double>() * to_si;
}

::testing::AssertionResult same(const Vec3& simulated, const Vec3& printed) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(simulated[i] - printed[i]) > 1e-12 * std::abs(printed[i]) + 1e-300 ||
        (printed[i] == 0) != (simulated[i] == 0))
      return ::testing::AssertionFailure() << "axis " << "xyz"[i] << ": simulated " << simulated[i] << ", printed "
                                           << printed[i];
  return ::testing::AssertionSuccess();
}

// Independent conversions (SI of one paper unit).
const double deg_h = kPiDeg / 3600.0, deg_sqrt_h = kPiDeg / 60.0, deg_h_sqrt_h = kPiDeg / 3600.0 / 60.0;
const double arcsec = kPiDeg / 3600.0;
const double m_h = 1.0 / 3600.0, mps_h = 1.0 / 3600.0, mps_sqrt_h = 1.0 / 60.0, mps_h_sqrt_h = 1.0 / 216000.0,
             mps_h2 = 1.0 / 12960000.0, mg = 9.80665e-3;

void expect_absent(const TriadErrorModel& m, bool Q, bool N, bool B, bool K, bool R, const std::string& what) {
  if (Q) {
    EXPECT_TRUE(m.quantization_Q.isZero()) << what << " Q";
  }
  if (N) {
    EXPECT_TRUE(m.white_N.isZero()) << what << " N";
  }
  if (B) {
    EXPECT_TRUE(m.instability_B.isZero()) << what << " B";
  }
  if (K) {
    EXPECT_TRUE(m.rate_rw_K.isZero()) << what << " K";
  }
  if (R) {
    EXPECT_TRUE(m.ramp_R.isZero()) << what << " R";
  }
  EXPECT_TRUE(m.sinusoid_amplitude.isZero()) << what;
  EXPECT_FALSE(m.quantization_rounding) << what;
}
}  // namespace

namespace {
// Table 3's run-to-run constants of a Honeywell grade (both datasheets print the same six figures).
void expect_honeywell_datasheet(const ImuGrade& g, const char* ds) {
  EXPECT_TRUE(same(g.gyro.turn_on_bias_std, Vec3::Constant(datasheet(ds, "gyro_bias_repeatability_deg_h", deg_h))));
  EXPECT_TRUE(same(g.gyro.scale_std, Vec3::Constant(datasheet(ds, "gyro_scale_factor_linearity_ppm", 1e-6))));
  EXPECT_TRUE(same(g.gyro.non_orthogonality_std, Vec3::Constant(datasheet(ds, "gyro_non_orthogonality_urad", 1e-6))));
  EXPECT_TRUE(same(g.accel.turn_on_bias_std, Vec3::Constant(datasheet(ds, "accel_bias_repeatability_mg", mg))));
  EXPECT_TRUE(same(g.accel.scale_std, Vec3::Constant(datasheet(ds, "accel_scale_factor_repeatability_ppm", 1e-6))));
  EXPECT_TRUE(same(g.accel.non_orthogonality_std, Vec3::Constant(datasheet(ds, "accel_non_orthogonality_urad", 1e-6))));
}
}  // namespace

TEST(SimGrades, Hg1700IsTables4And5AndItsDatasheet) {
  for (const char* name : {"hg1700", "hg1700-paper"}) {
    SCOPED_TRACE(name);
    const ImuGrade g = imu_grade(name);
    EXPECT_EQ(g.name, name);
    EXPECT_TRUE(same(g.gyro.quantization_Q, row("table5_hg1700_gyro", "Q_arcsec", arcsec)));
    EXPECT_TRUE(same(g.gyro.white_N, row("table5_hg1700_gyro", "N_deg_sqrt_h", deg_sqrt_h)));
    expect_absent(g.gyro, false, false, true, true, true, "hg1700 gyro");  // Table 5: Q + N only
    EXPECT_TRUE(same(g.accel.quantization_Q, row("table4_hg1700_accel", "Q_m_h", m_h)));
    EXPECT_TRUE(same(g.accel.white_N, row("table4_hg1700_accel", "N_mps_sqrt_h", mps_sqrt_h)));
    EXPECT_TRUE(same(g.accel.instability_B, row("table4_hg1700_accel", "B_mps_h", mps_h)));
    EXPECT_TRUE(same(g.accel.instability_T_s, row("table4_hg1700_accel", "B_time_constant_s", 1.0)));
    EXPECT_TRUE(same(g.accel.rate_rw_K, row("table4_hg1700_accel", "K_mps_h_sqrt_h", mps_h_sqrt_h)));
    expect_absent(g.accel, false, false, false, false, true, "hg1700 accel");  // Q + N + B + K
    expect_honeywell_datasheet(g, "HG1700_AG58");
  }
}

TEST(SimGrades, Hg1900IsTables6And7AndItsDatasheet) {
  for (const char* name : {"hg1900", "hg1900-paper"}) {
    SCOPED_TRACE(name);
    const ImuGrade g = imu_grade(name);
    EXPECT_EQ(g.name, name);
    EXPECT_TRUE(same(g.gyro.white_N, row("table7_hg1900_gyro", "N_deg_sqrt_h", deg_sqrt_h)));
    EXPECT_TRUE(same(g.gyro.instability_B, row("table7_hg1900_gyro", "B_deg_h", deg_h)));
    EXPECT_TRUE(same(g.gyro.instability_T_s, row("table7_hg1900_gyro", "B_time_constant_s", 1.0)));
    EXPECT_TRUE(same(g.gyro.rate_rw_K, row("table7_hg1900_gyro", "K_deg_h_sqrt_h", deg_h_sqrt_h)));
    expect_absent(g.gyro, true, false, false, false, true, "hg1900 gyro");  // N + B + K
    EXPECT_TRUE(same(g.accel.quantization_Q, row("table6_hg1900_accel", "Q_m_h", m_h)));
    EXPECT_TRUE(same(g.accel.instability_B, row("table6_hg1900_accel", "B_mps_h", mps_h)));
    EXPECT_TRUE(same(g.accel.instability_T_s, row("table6_hg1900_accel", "B_time_constant_s", 1.0)));
    EXPECT_TRUE(same(g.accel.rate_rw_K, row("table6_hg1900_accel", "K_mps_h_sqrt_h", mps_h_sqrt_h)));
    EXPECT_TRUE(same(g.accel.ramp_R, row("table6_hg1900_accel", "R_mps_h2", mps_h2)));  // Y: null -> absent
    EXPECT_EQ(g.accel.ramp_R.y(), 0.0);
    expect_absent(g.accel, false, true, false, false, false, "hg1900 accel");  // Q + B + K + R, N insignificant
    expect_honeywell_datasheet(g, "HG1900_CA29");
  }
}

TEST(SimGrades, Gx2IsTables8And9WithQAsPrintedAndTheArcsecReadingBeside) {
  for (const char* name : {"3dm-gx2", "3dmgx2", "gx2", "3dm-gx2-paper", "3dm-gx2-q-arcsec", "3dm-gx2-paper-q-arcsec"}) {
    SCOPED_TRACE(name);
    const ImuGrade g = imu_grade(name);
    const bool arcsec_reading = std::string(name).find("q-arcsec") != std::string::npos;
    const bool alias = std::string(name) == "3dmgx2" || std::string(name) == "gx2";
    EXPECT_EQ(g.name, alias ? std::string("3dm-gx2") : std::string(name));
    // Table 9 prints Q in degrees; the second grade reads the same numbers as arcsec.
    EXPECT_TRUE(same(g.gyro.quantization_Q, row("table9_3dm_gx2_gyro", "Q_deg", arcsec_reading ? arcsec : kPiDeg)));
    EXPECT_TRUE(same(g.gyro.white_N, row("table9_3dm_gx2_gyro", "N_deg_sqrt_h", deg_sqrt_h)));
    EXPECT_TRUE(same(g.gyro.instability_B, row("table9_3dm_gx2_gyro", "B_deg_h", deg_h)));
    EXPECT_TRUE(same(g.gyro.instability_T_s, row("table9_3dm_gx2_gyro", "B_time_constant_s", 1.0)));
    EXPECT_TRUE(same(g.gyro.rate_rw_K, row("table9_3dm_gx2_gyro", "K_deg_h_sqrt_h", deg_h_sqrt_h)));
    expect_absent(g.gyro, false, false, false, false, true, "gx2 gyro");
    EXPECT_TRUE(same(g.accel.quantization_Q, row("table8_3dm_gx2_accel", "Q_m_h", m_h)));
    EXPECT_TRUE(same(g.accel.white_N, row("table8_3dm_gx2_accel", "N_mps_sqrt_h", mps_sqrt_h)));
    EXPECT_TRUE(same(g.accel.instability_B, row("table8_3dm_gx2_accel", "B_mps_h", mps_h)));
    EXPECT_TRUE(same(g.accel.instability_T_s, row("table8_3dm_gx2_accel", "B_time_constant_s", 1.0)));
    EXPECT_TRUE(same(g.accel.rate_rw_K, row("table8_3dm_gx2_accel", "K_mps_h_sqrt_h", mps_h_sqrt_h)));
    expect_absent(g.accel, false, false, false, false, true, "gx2 accel");
    const char* ds = "3DM-GX2";
    EXPECT_TRUE(same(g.gyro.turn_on_bias_std, Vec3::Constant(datasheet(ds, "gyro_bias_repeatability_deg_s", kPiDeg))));
    EXPECT_TRUE(same(g.gyro.scale_std, Vec3::Constant(datasheet(ds, "gyro_scale_factor_linearity_percent", 1e-2))));
    EXPECT_TRUE(same(g.accel.turn_on_bias_std, Vec3::Constant(datasheet(ds, "accel_bias_in_run_stability_g", 9.80665))));
    EXPECT_TRUE(
        same(g.accel.scale_std, Vec3::Constant(datasheet(ds, "accel_scale_factor_repeatability_percent", 1e-2))));
    EXPECT_TRUE(g.gyro.non_orthogonality_std.isZero());  // none printed
    EXPECT_TRUE(g.accel.non_orthogonality_std.isZero());
  }
}

TEST(SimGrades, TheTypicalStandInsExistBesideThePaperGrades) {
  EXPECT_EQ(imu_grade_names(), (std::vector<std::string>{"perfect", "hg1700", "hg1900", "3dm-gx2", "3dm-gx2-q-arcsec",
                                                         "hg1700-typical", "hg1900-typical", "3dm-gx2-typical"}));
  for (const char* name : {"hg1700-typical", "hg1900-typical", "3dm-gx2-typical"}) {
    SCOPED_TRACE(name);
    const ImuGrade g = imu_grade(name);
    EXPECT_EQ(g.name, name);
    // Datasheet-level values with typical in-run terms on every axis, quantisation as ADC rounding.
    for (const TriadErrorModel* t : {&g.gyro, &g.accel}) {
      EXPECT_TRUE(t->quantization_rounding);
      EXPECT_TRUE((t->white_N.array() > 0).all());
      EXPECT_TRUE((t->instability_B.array() > 0).all());
      EXPECT_TRUE((t->rate_rw_K.array() > 0).all());
      EXPECT_TRUE((t->ramp_R.array() != 0).all());
    }
    EXPECT_EQ(builtin_grade_yaml(name), "");  // no file form
  }
  // Not the paper's: Table 5 identifies no bias instability of the HG1700 gyro; the typical grade has one.
  EXPECT_TRUE(imu_grade("hg1700").gyro.instability_B.isZero());
  EXPECT_FALSE(imu_grade("hg1700-typical").gyro.instability_B.isZero());
}

TEST(SimGrades, EveryBuiltInReadsBackFromItsPrintedYamlAndTheExampleLoads) {
  std::vector<std::string> names = imu_grade_names();
  for (const char* alias : {"hg1700-paper", "hg1900-paper", "3dm-gx2-paper", "3dm-gx2-paper-q-arcsec"})
    names.push_back(alias);
  for (const auto& name : names) {
    // The paper's grades (and their -paper aliases) have a file form; perfect and the -typical stand-ins none.
    const bool paper = name != "perfect" && name.find("-typical") == std::string::npos;
    const std::string text = builtin_grade_yaml(name);
    ASSERT_EQ(text.empty(), !paper) << name;
    if (!paper) continue;
    const std::string path = write_text("grade_" + name + ".yaml", text);
    const ImuGrade a = imu_grade(name), b = imu_grade(path);
    EXPECT_EQ(b.name, name);
    for (auto [x, y] : {std::pair{&a.gyro, &b.gyro}, std::pair{&a.accel, &b.accel}}) {
      EXPECT_EQ(x->quantization_Q, y->quantization_Q);
      EXPECT_EQ(x->white_N, y->white_N);
      EXPECT_EQ(x->instability_B, y->instability_B);
      EXPECT_EQ(x->instability_T_s, y->instability_T_s);
      EXPECT_EQ(x->rate_rw_K, y->rate_rw_K);
      EXPECT_EQ(x->ramp_R, y->ramp_R);
      EXPECT_EQ(x->turn_on_bias_std, y->turn_on_bias_std);
      EXPECT_EQ(x->scale_std, y->scale_std);
      EXPECT_EQ(x->non_orthogonality_std, y->non_orthogonality_std);
    }
  }
  const ImuGrade e = imu_grade(LDV_SIM_GRADES_DIR "/example.yaml");
  EXPECT_EQ(e.name, "example-tactical");
  EXPECT_NEAR(e.gyro.quantization_Q.z(), 12 * arcsec, 1e-18);
  EXPECT_NEAR(e.gyro.ramp_R.x(), 0.02 * deg_h / 3600.0, 1e-20);
  EXPECT_EQ(e.gyro.ramp_R.y(), 0.0);
  EXPECT_NEAR(e.accel.turn_on_bias_std.x(), 1 * mg, 1e-15);
  EXPECT_NEAR(e.accel.instability_T_s.y(), 120.0, 0);
  // A simulation with it runs (the file's path is the grade).
  SimRequest r = perfect_request("static", 2.0);
  r.grade = LDV_SIM_GRADES_DIR "/example.yaml";
  r.with_noise = true;
  EXPECT_EQ(simulate(r).imu.size(), 200u);
}

TEST(SimGrades, BadGradeFilesNameTheFileTheLineAndTheKey) {
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {"gyro:\n  N_deg_sqrt_h: 0.1\n  Q_arcsex: 3\n", ":3: unknown key 'gyro.Q_arcsex' (did you mean 'gyro.Q_arcsec'?)"},
      {"gyro:\n  N_deg_sqrt_h: [0.1, 0.2]\n", ":2: key 'gyro.N_deg_sqrt_h': expected a number (every axis) or a list of 3"},
      {"accel:\n  N_mps_sqrt_h: -0.1\n", ":2: key 'accel.N_mps_sqrt_h': expected a number >= 0, found -0.1"},
      {"accel:\n  B_mps_h: 0.1\n", ":2: key 'accel.B_mps_h': needs its Gauss-Markov time constant"},
      {"accel:\n  B_mps_h: 0.1\n  B_time_constant_s: [10, 0, 10]\n",
       ":3: key 'accel.B_time_constant_s': expected a positive time constant [s] on axis y"},
      {"gyro:\n  Q_deg: 0.1\n  Q_arcsec: 3\n", "key 'gyro.Q_arcsec': expected one unit for this term, but 'Q_deg'"},
      {"gyro:\n  K_deg_h_sqrt_h: [1, fast, 2]\n", ":2: key 'gyro.K_deg_h_sqrt_h': expected a number or null (element 2), found 'fast'"},
      {"gyro:\n  quantization: round\n", ":2: key 'gyro.quantization': expected 'white'"},
      {"gyros:\n  N_deg_sqrt_h: 1\n", ":1: unknown key 'gyros' (did you mean 'gyro'?)"},
      {"gyro: [1, 2\n", "YAML syntax error"},
      {"name: x\n", "expected a 'gyro:' and/or an 'accel:' section"},
  };
  for (const Case& k : cases) {
    const std::string path = write_text("bad_grade.yaml", k.text);
    const std::string msg = input_error_of([&] { imu_grade(path); });
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;  // starts with the file name
    EXPECT_NE(msg.find(k.message), std::string::npos) << k.text << "\n -> " << msg;
  }
  EXPECT_NE(input_error_of([] { imu_grade("/nonexistent/grade.yaml"); }).find("--grade: cannot read the grade file"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { imu_grade("hg2000"); })
                .find("--grade: unknown IMU grade 'hg2000': expected one of perfect, hg1700, hg1900, 3dm-gx2, "
                      "3dm-gx2-q-arcsec, hg1700-typical, hg1900-typical, 3dm-gx2-typical, or a grade YAML file"),
            std::string::npos);
}

TEST(SimGrades, TheKfGinsConfigTakesTheMeanCorrelationTimeOfTheAxesWithAB) {
  SimRequest r = perfect_request("static", 2.0);
  for (const char* name : {"hg1700", "hg1900", "3dm-gx2"}) {
    r.grade = name;
    const SimResult s = simulate(r);
    const ImuGrade g = imu_grade(name);
    double sum = 0;
    int n = 0;
    for (const TriadErrorModel* t : {&g.gyro, &g.accel})
      for (int i = 0; i < 3; ++i)
        if (t->instability_B[i] > 0) sum += t->instability_T_s[i], ++n;
    const double T = sum / n;
    EXPECT_NEAR(s.kfgins.imu_noise.corr_time_s, T, 1e-9) << name;
    // gbstd = sqrt(B^2 + K^2 T / 2); the turn-on bias only in the initial std.
    const Vec3 gb = (g.gyro.instability_B.cwiseAbs2() + g.gyro.rate_rw_K.cwiseAbs2() * (T / 2)).cwiseSqrt();
    EXPECT_LT((s.kfgins.imu_noise.gyro_bias_std_rad_s - gb).norm(), 1e-15) << name;
    ASSERT_TRUE(s.kfgins.init_gyro_bias_std_rad_s.has_value());
    EXPECT_LT((*s.kfgins.init_gyro_bias_std_rad_s -
               (g.gyro.turn_on_bias_std.cwiseAbs2() + gb.cwiseAbs2()).cwiseSqrt()).norm(), 1e-15) << name;
  }
  EXPECT_NEAR(simulate([&] { r.grade = "hg1700"; return r; }()).kfgins.imu_noise.corr_time_s, 160.0, 1e-9);
}

TEST(SimGrades, TheDrawnNonOrthogonalityIsInTheAnswerKey) {
  SimRequest r = perfect_request("static", 2.0);
  r.grade = "hg1900";
  const SimResult s = simulate(r);
  ASSERT_TRUE(s.injected_effects.count("gyro_misalignment"));
  ASSERT_TRUE(s.injected_effects.count("accel_misalignment"));
  for (double m : s.injected_effects.at("gyro_misalignment")) {
    EXPECT_NE(m, 0.0);
    EXPECT_LT(std::abs(m), 5 * 200e-6);
  }
  r.grade = "3dm-gx2";  // no non-orthogonality printed: none drawn
  EXPECT_FALSE(simulate(r).injected_effects.count("gyro_misalignment"));
}
