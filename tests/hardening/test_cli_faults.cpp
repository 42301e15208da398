// Regression corpus of issue 13's crashes and hangs in the `ldv` commands: given the input or option that
// crashed, hung or exhausted memory, when ldv runs, then it ends with a clear error naming what was wrong,
// or handles it correctly and counts it; never a signal, never past its time limit.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "cli_run.hpp"
#include "common/bus/lcm_log_reader.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/atomic_file.hpp"
#include "common/io/input_error.hpp"
#include "common/parallel/parallel_for.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "sim/simulator.hpp"
#include "toolbox/allan/noise_fit.hpp"
#include "toolbox/assess/outage_plan.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;
using test::is_clear_error;
using test::run_ldv;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("ldv_faults_" + std::to_string(getpid()) + "_" + name);
  fs::create_directories(d);
  return d;
}

// A tactical-grade straight run of `duration_s` with 5 Hz GNSS written as `ldv sim` writes it, in dir/sim.
fs::path simulated_files(const fs::path& dir, double duration_s) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.duration_s = duration_s;
  req.gnss_rate_hz = 5.0;
  sim::SimResult s = sim::simulate(req);
  sim::write_outputs(s, (dir / "sim").string());
  return dir / "sim";
}

// White rate noise as a CSV with a time column (an accelerometer-like channel).
fs::path write_rate_csv(const fs::path& dir, double scale, int rows, double dt_s = 0.01) {
  const fs::path p = dir / ("rate_" + std::to_string(rows) + ".csv");
  std::ofstream f(p);
  f.precision(17);
  f << "t,acc\n";
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < rows; ++i) f << i * dt_s << "," << scale * n(rng) << "\n";
  return p;
}

// A one-minute simulated tactical drive written as KF-GINS files (kfgins.yaml, imu.txt, gnss.txt, ...).
const fs::path& drive_dir() {
  static const fs::path d = [] {
    const fs::path dir = temp_dir("drive");
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.seed = 11;
    req.duration_s = 90.0;
    req.scenario = "drive";
    req.gnss_rate_hz = 5.0;
    sim::SimResult result = sim::simulate(req);
    sim::write_outputs(result, (dir / "drive").string());
    return dir / "drive";
  }();
  return d;
}

}  // namespace

// --- ldv allan --------------------------------------------------------------------------------------

TEST(AllanFaults, EmptyTermListIsAClearError) {
  const fs::path csv = write_rate_csv(temp_dir("allan_terms"), 1e-3, 3000);
  const auto r = run_ldv({"allan", csv.string(), "--time-column", "t", "--terms", "", "--curve-only"});
  EXPECT_EQ(r.signal, 0) << r.output;
  EXPECT_FALSE(r.timed_out);
  // Either refused up front or reported as a fit error per channel; never a crash.
  EXPECT_NE(r.output.find("term"), std::string::npos) << r.output;
}

TEST(AllanFaults, HugeDataIsFittedOrRefusedClearly) {
  // 1e200 squared overflows: the fit scales the deviations, so the white noise is identified at scale.
  const fs::path csv = write_rate_csv(temp_dir("allan_huge"), 1e150, 3000);
  const auto r = run_ldv({"allan", csv.string(), "--time-column", "t", "--curve-only"});
  EXPECT_EQ(r.signal, 0) << r.output;
  EXPECT_FALSE(r.timed_out);
  const fs::path csv200 = write_rate_csv(temp_dir("allan_huge200"), 1e200, 3000);
  const auto r200 = run_ldv({"allan", csv200.string(), "--time-column", "t", "--curve-only"});
  EXPECT_EQ(r200.signal, 0) << r200.output;
  EXPECT_FALSE(r200.timed_out);
}

TEST(AllanFaults, NoiseFitIsScaleFree) {
  // White noise N = 1 at tau0 = 1: AVAR = N^2 / tau. The fit of the same curve scaled by 1e120 must give
  // N scaled by 1e120 (the fit squares twice: unscaled it would overflow).
  std::vector<allan::StabilityPoint> pts;
  for (long m = 1; m <= 256; m *= 2) {
    allan::StabilityPoint p;
    p.point.m = m;
    p.point.tau_s = static_cast<double>(m);
    p.point.n_terms = 10000 - 2 * m;
    p.point.dev = 1e120 / std::sqrt(static_cast<double>(m));
    p.edf = 1000.0 / static_cast<double>(m);
    pts.push_back(p);
  }
  allan::FitOptions opt;
  opt.q = opt.r = false;
  const allan::NoiseFit f = allan::fit_noise_model(pts, opt);
  EXPECT_NEAR(f[allan::ModelTerm::kN].value / 1e120, 1.0, 1e-3);
  opt.q = opt.n = opt.b = opt.k = opt.r = opt.gauss_markov = opt.sinusoid = false;
  EXPECT_THROW(allan::fit_noise_model(pts, opt), std::invalid_argument);
}

TEST(AllanFaults, TinyTau0IsRefused) {
  const fs::path csv = write_rate_csv(temp_dir("allan_tau0"), 1e-3, 3000);
  for (const char* tau0 : {"1e-300", "nan", "0", "-1", "inf"}) {
    const auto r = run_ldv({"allan", csv.string(), "--tau0", tau0});
    EXPECT_TRUE(is_clear_error(r)) << tau0 << ": " << r.output;
    EXPECT_NE(r.output.find("tau0"), std::string::npos) << r.output;
  }
}

TEST(AllanFaults, AllTausOnATwoMinuteRecordIsBounded) {
  // 12000 samples, `--taus all`: 3000 taus. The GLS fit is cubic in the number of points: it fits a
  // log-spaced subset, so this takes seconds (it took minutes and 2.2 GB).
  const fs::path csv = write_rate_csv(temp_dir("allan_all"), 1e-3, 12000);
  const auto r =
      run_ldv({"allan", csv.string(), "--time-column", "t", "--taus", "all", "--curve-only"}, 60.0, 1L << 30);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(r.timed_out);
}

// --- ldv diagnose, outage, nav: options ------------------------------------------------------------

TEST(OptionFaults, OutOfRangeAndNonFiniteValuesAreRefused) {
  const std::string cfg = (drive_dir() / "kfgins.yaml").string();
  const std::vector<std::vector<std::string>> bad = {
      {"diagnose", "--kfgins-config", cfg, "--max-add", "-1"},
      {"outage", "--kfgins-config", cfg, "--lengths", "nan"},
      {"outage", "--kfgins-config", cfg, "--lengths", "0"},
      {"outage", "--kfgins-config", cfg, "--lengths", "-10"},
      {"outage", "--kfgins-config", cfg, "--lengths", "10,1e999"},
      {"outage", "--kfgins-config", cfg, "--recovery", "nan"},
      {"outage", "--kfgins-config", cfg, "--recovery", "-1"},
      {"nav", "--kfgins-config", cfg, "--align-hypotheses", "100000000"},
      {"nav", "--kfgins-config", cfg, "--imu-time-shift", "nan"},
      {"nav", "--kfgins-config", cfg, "--lever", "nan", "0", "0"},
  };
  for (const auto& args : bad) {
    const auto r = run_ldv(args, 60.0);
    std::string line;
    for (const auto& a : args) line += a + " ";
    EXPECT_TRUE(is_clear_error(r)) << line << "\n" << r.output;
  }
}

TEST(OptionFaults, ManyThreadsAreClampedNotFatal) {
  const std::string cfg = (drive_dir() / "kfgins.yaml").string();
  const auto r = run_ldv({"outage", "--kfgins-config", cfg, "--threads", "100000", "--lengths", "10", "--converge",
                          "20", "--recovery", "10", "--quiet"},
                         240.0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(OptionFaults, ParallelForCarriesOnWhenThreadsCannotStart) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "needs RLIMIT_AS, which AddressSanitizer's shadow memory cannot run under";
#endif
  // In a child with a small address space, most of 256 thread stacks cannot be mapped: every job must
  // still run exactly once on the threads that did start.
  const pid_t pid = fork();
  if (pid == 0) {
    const rlimit mem{512L << 20, 512L << 20};
    setrlimit(RLIMIT_AS, &mem);
    std::vector<std::atomic<int>> done(2000);
    std::vector<size_t> order(done.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const int threads = parallel_for(order, 100000, [&](size_t i) { done[i]++; });
    for (auto& d : done)
      if (d.load() != 1) _exit(2);
    _exit(threads >= 1 && threads <= kMaxWorkerThreads ? 0 : 3);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "child killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

// --- outage planner, filter inputs ----------------------------------------------------------------

TEST(PlanFaults, NonPositiveOrNanLengthsAreRefusedNotPlannedForever) {
  std::vector<GnssFix> g(100);
  for (size_t i = 0; i < g.size(); ++i) {
    g[i].t_s = static_cast<double>(i);
    g[i].pos = {0.5, 2.0, 10.0};
    g[i].pos.lat_rad += 1e-6 * static_cast<double>(i);
  }
  assess::OutagePlanOptions o;
  for (double bad : {0.0, -5.0, std::nan(""), HUGE_VAL})
    EXPECT_THROW(assess::plan_outages(g, {bad}, 100.0, o), std::invalid_argument);
  o.recovery_s = NAN;
  EXPECT_THROW(assess::plan_outages(g, {10.0}, 100.0, o), std::invalid_argument);
}

TEST(FilterFaults, NanOrAbsurdInitialStateAndOptionsAreRefused) {
  est::FilterOptions o;
  o.lever_arm.init = Vec3(NAN, 0, 0);
  EXPECT_THROW(est::NavFilter{o}, std::invalid_argument);
  o = est::FilterOptions();
  o.time_offset_init_s = 1e9;
  EXPECT_THROW(est::NavFilter{o}, std::invalid_argument);
  est::NavFilter f{est::FilterOptions()};
  est::NavState s;
  s.pos = {NAN, 0.0, 0.0};
  EXPECT_THROW(f.initialize(s, est::NavStd{}), std::invalid_argument);
  s.pos = {0.5, 0.0, -1e9};
  EXPECT_THROW(f.initialize(s, est::NavStd{}), std::invalid_argument);
}

TEST(FilterFaults, AHoleInTheImuDataIsCoastedAndCountedNotIntegrated) {
  // Given a vehicle at rest, level, with 5 Hz GNSS; when the IMU data has a 1e6 s hole (a sample whose
  // increment says it spans the hole), then the hole is counted, the covariance opened (the state inside
  // its own 3 sigma), and the solution back on the fixes within two seconds. Before: the increment was
  // integrated over 1e6 s (height -4.6e15 m, "gaps 0").
  est::NavFilter f{est::FilterOptions()};
  est::NavState s;
  s.pos = {0.5, 2.0, 100.0};
  f.initialize(s, est::NavStd{});
  const double g = 9.8;
  auto at_rest = [&](double t, double dt) {
    ImuIncrement in;
    in.t_s = t;
    in.dt_s = dt;
    in.dvel_b_mps = Vec3(0, 0, -g * dt);
    return in;
  };
  GnssFix fix;
  fix.pos = s.pos;
  fix.pos_std_ned_m = Vec3::Constant(0.02);
  double t = 0.0;
  for (int i = 0; i < 100; ++i) f.add_imu(at_rest(t += 0.01, 0.01));
  f.add_imu(at_rest(t += 1e6, 1e6));
  EXPECT_GE(f.faults().imu_gaps, 1);
  EXPECT_NEAR(f.state().t_s, t, 1e-6);
  EXPECT_GT(f.covariance()(2, 2), 1e4);  // the hole's uncertainty shows
  EXPECT_LT(std::abs(f.state().pos.h_m - 100.0), 3.0 * std::sqrt(f.covariance()(2, 2)));
  for (int i = 0; i < 200; ++i) {
    if (i % 20 == 0) {
      fix.t_s = t + 0.01;
      f.add_gnss(fix);
    }
    f.add_imu(at_rest(t += 0.01, 0.01));
  }
  EXPECT_LT(earth::ned_between(s.pos, f.state().pos).norm(), 0.5);
}

// --- LCM logs -----------------------------------------------------------------------------------

namespace {
void put_be(std::ofstream& f, uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) f.put(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_event(std::ofstream& f, int64_t n, const std::string& channel, const std::string& data,
               int64_t claimed_data_bytes = -1) {
  put_be(f, LcmLogReader::kSyncWord, 4);
  put_be(f, static_cast<uint64_t>(n), 8);
  put_be(f, 1000000u * static_cast<uint64_t>(n), 8);
  put_be(f, channel.size(), 4);
  put_be(f, static_cast<uint64_t>(claimed_data_bytes >= 0 ? claimed_data_bytes : static_cast<int64_t>(data.size())), 4);
  f << channel << data;
}
}  // namespace

TEST(LcmLogFaults, CorruptLengthsAreSkippedAndEverythingAfterThemIsRead) {
  const fs::path p = temp_dir("lcmlog") / "bad.lcm";
  {
    std::ofstream f(p, std::ios::binary);
    put_event(f, 1, "A", "aaaa");
    put_event(f, 2, "X", "xxxx", 0x7fffffffLL);  // says 2 GB
    put_event(f, 3, "B", "bbbbbb");
    put_event(f, 4, "Y", "yyyyyyyyyyyy", 5);  // a plausible but wrong length: does not end at a sync word
    put_event(f, 5, "C", "c");
    put_event(f, 6, "D", "dddd", 4000);  // cut short by the end of the file
  }
  LcmLogReader r(p.string());
  LcmLogEvent ev;
  std::string channels;
  while (r.next(ev)) channels += ev.channel;
  EXPECT_EQ(channels, "ABC");
  EXPECT_EQ(r.corrupt_events(), 2);
  EXPECT_EQ(r.truncated_events(), 1);

  // The commands that crashed inside liblcm on such a log now read it and say what they skipped.
  const auto ex = run_ldv({"export", p.string(), "--out", (p.parent_path() / "export").string()});
  EXPECT_EQ(ex.exit_code, 0) << ex.output;
  EXPECT_NE(ex.output.find("3 corrupt log events"), std::string::npos) << ex.output;
  EXPECT_THROW(LcmLogReader("/dev/zero"), InputError);
}

// Issue 35, item 30: a 24000-event log whose event 12000 says 2 GB lost the 12000 after it (reported). The reader
// resynchronises on the next sync word: 23999 events come back, one counted corrupt, none after it lost.
TEST(LcmLogFaults, GivenA2GbLengthInTheMiddleOfALongLog_ThenEveryEventAfterItIsRead) {
  const fs::path p = temp_dir("lcmlog") / "long.lcm";
  {
    std::ofstream f(p, std::ios::binary);
    const std::string data(100, '\x5a');
    for (int k = 0; k < 24000; ++k) put_event(f, k, "IMU", data, k == 12000 ? 0x7fffffffLL : -1);
  }
  LcmLogReader r(p.string());
  LcmLogEvent ev;
  long events = 0, last_number = -1;
  while (r.next(ev)) ++events, last_number = ev.event_number;
  EXPECT_EQ(events, 23999);
  EXPECT_EQ(last_number, 23999);
  EXPECT_EQ(r.corrupt_events(), 1);
}

// Issue 46, item 2: the same 2 GB length in a real drive's log, through the commands that read logs: `ldv export`
// and `ldv nav --lcm-log` lost the 12000 IMU after it. Every IMU message after it is exported and navigated.
TEST(LcmLogFaults, GivenA2GbLengthInADrivesLog_ThenExportAndNavReadEverythingAfterIt) {
  const fs::path dir = temp_dir("lcmlog_drive");
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.scenario = "drive";
  req.duration_s = 120.0;
  req.gnss_rate_hz = 5.0;
  req.start_sow_s = 345600.0;
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, (dir / "sim").string());
  const int week = 2300;
  const fs::path log = dir / "drive.lcmlog";
  const size_t corrupted = sim.imu.size() / 2;
  {
    std::ofstream f(log, std::ios::binary);
    auto bytes = [](const auto& m) {
      std::string b(static_cast<size_t>(m.getEncodedSize()), '\0');
      m.encode(b.data(), 0, static_cast<int>(b.size()));
      return b;
    };
    int64_t n = 0;
    size_t g = 0;
    for (size_t i = 0; i < sim.imu.size(); ++i) {
      for (; g < sim.gnss.size() && sim.gnss[g].t_s <= sim.imu[i].t_s; ++g)
        put_event(f, n++, "GNSS_SOLUTION", bytes(message_from_gnss(sim.gnss[g], week, static_cast<int64_t>(g))));
      const std::string imu = bytes(message_from_imu(sim.imu[i], week, static_cast<int64_t>(i)));
      put_event(f, n++, "IMU", imu, i == corrupted ? 0x7fffffffLL : -1);
    }
  }
  const auto ex = run_ldv({"export", log.string(), "--out", (dir / "export").string()}, 120.0);
  ASSERT_EQ(ex.exit_code, 0) << ex.output;
  long imu_lines = 0;
  {
    std::ifstream in(dir / "export" / "imu.txt");
    for (std::string line; std::getline(in, line);) imu_lines += !line.empty() && line[0] != '#';
  }
  // The one IMU message lost in the corrupt event is bridged (and said); none after it is lost.
  EXPECT_EQ(imu_lines, static_cast<long>(sim.imu.size())) << ex.output;
  EXPECT_NE(ex.output.find("1 corrupt log events skipped"), std::string::npos) << ex.output;
  EXPECT_NE(ex.output.find("1 lost IMU samples bridged"), std::string::npos) << ex.output;

  const auto nav = run_ldv({"nav", "--lcm-log", log.string(), "--kfgins-config", (dir / "sim" / "kfgins.yaml").string(),
                            "--out", (dir / "nav" / "from_log.nav").string()},
                           120.0);
  ASSERT_EQ(nav.exit_code, 0) << nav.output;
  EXPECT_NE(nav.output.find(std::to_string(sim.imu.size() - 1) + " IMU"), std::string::npos) << nav.output;
  // Issue 46 (5): the drive starts with 60 s standing still; the summary said "no standstill in the data".
  EXPECT_EQ(nav.output.find("no standstill"), std::string::npos) << nav.output;
  EXPECT_NE(nav.output.find("s standstill in the data showed"), std::string::npos) << nav.output;
  double last_sow = 0.0;
  {
    std::ifstream in(dir / "nav" / "from_log.nav");
    double week_column = 0.0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream row(line);
      if (!line.empty() && line[0] != '#') row >> week_column >> last_sow;  // KF-GINS .nav: week, seconds of week, ...
    }
  }
  EXPECT_NEAR(last_sow, sim.imu.back().t_s, 0.5) << "the navigation stopped at the corrupt event";

  // `ldv spy` on the log (file://) crashed inside LCM's file provider (SIGSEGV) and, on a sound log, never ended:
  // it reads the log to its end, counts every message and shows the last one's time.
  const auto spy = run_ldv({"spy", "--once", "--url", "file://" + log.string()}, 60.0);
  ASSERT_EQ(spy.exit_code, 0) << spy.output;
  EXPECT_NE(spy.output.find(std::to_string(sim.imu.size() - 1)), std::string::npos) << spy.output;
  EXPECT_NE(spy.output.find("1 corrupt log events skipped"), std::string::npos) << spy.output;
  char last_imu[64];
  std::snprintf(last_imu, sizeof last_imu, "sow %.4f", sim.imu.back().t_s);
  EXPECT_NE(spy.output.find(last_imu), std::string::npos) << spy.output;
}

}  // namespace ldv

namespace ldv {

TEST(WriterFaults, AnOutputPathThatIsNotARegularFileIsNeverReplaced) {
  // `ldv diagnose --write-config /dev/zero` once renamed its temporary file over /dev/zero. A FIFO and a
  // link stand in for the device here: neither may be replaced, and the command says it cannot write.
  const fs::path dir = temp_dir("writer");
  const fs::path fifo = dir / "fifo", link = dir / "link";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
  fs::create_symlink("/dev/null", link);
  EXPECT_FALSE(write_file_atomically(fifo.string(), "text"));
  EXPECT_FALSE(write_file_atomically(link.string(), "text"));
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_TRUE(write_file_atomically((dir / "plain.txt").string(), "text"));
}

}  // namespace ldv

namespace ldv {

// Issue 35, item 25: `ldv export` of fixes without a velocity wrote 13 columns with a velocity std of 0 (ldv nav
// then dropped every line), and a log across the week rollover came out sorted by seconds of week only.
TEST(LcmLogFaults, GivenALogAcrossAWeekRolloverWithoutGnssVelocity_ThenTheExportIsInTimeOrderAndReadable) {
  const fs::path p = temp_dir("export_rollover") / "run.lcm";
  {
    std::ofstream f(p, std::ios::binary);
    int64_t n = 0;
    for (int k = 0; k < 2000; ++k) {  // 10 s at 200 Hz from week 2300 sow 604795
      const double t = 604795.0 + 0.005 * (k + 1);
      const int week = t >= 604800.0 ? 2301 : 2300;
      ImuIncrement s;
      s.t_s = t - (week - 2300) * 604800.0;
      s.dt_s = 0.005;
      s.dvel_b_mps = Vec3(0, 0, -0.049);
      const ldv_lcm::imu_sample_t m = message_from_imu(s, week, k);
      std::string data(static_cast<size_t>(m.getEncodedSize()), '\0');
      m.encode(data.data(), 0, static_cast<int>(data.size()));
      put_event(f, n++, "IMU", data);
      if (k % 40 == 39) {
        GnssFix g;
        g.t_s = s.t_s;
        g.pos = {0.53, 1.99, 20.0};
        g.pos_std_ned_m = Vec3(0.01, 0.01, 0.02);
        const ldv_lcm::gnss_solution_t gm = message_from_gnss(g, week, k / 40);
        std::string gd(static_cast<size_t>(gm.getEncodedSize()), '\0');
        gm.encode(gd.data(), 0, static_cast<int>(gd.size()));
        put_event(f, n++, "GNSS_SOLUTION", gd);
      }
    }
  }
  const fs::path out = p.parent_path() / "export";
  const auto ex = run_ldv({"export", p.string(), "--out", out.string()});
  ASSERT_EQ(ex.exit_code, 0) << ex.output;
  GnssReadReport rep;
  const auto gnss = read_kfgins_gnss((out / "gnss.txt").string(), &rep);
  EXPECT_EQ(rep.columns, 7) << "no velocity: 7 columns";
  EXPECT_EQ(gnss.size(), 50u);
  EXPECT_EQ(rep.dropped.total(), 0);
  const auto imu = read_kfgins_imu((out / "imu.txt").string());
  ASSERT_EQ(imu.size(), 2000u);
  for (size_t i = 1; i < imu.size(); ++i) ASSERT_GT(imu[i].t_s, imu[i - 1].t_s) << i;
  EXPECT_NEAR(imu.back().t_s, 604805.0, 1e-6) << "seconds of the first week, on past the rollover";
}

// Issue 35, item 31: options and files that ran silently, printed inf, or hung.
TEST(CliFaults, GivenTermsWithNoKnownLetter_ThenAllanRefusesThemByName) {
  const fs::path csv = write_rate_csv(temp_dir("allan_xyz"), 1e-3, 3000);
  const auto r = run_ldv({"allan", csv.string(), "--time-column", "t", "--terms", "XYZ", "--curve-only"});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("--terms"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'X' is not a noise term"), std::string::npos) << r.output;
}

TEST(CliFaults, GivenAnAlphaOrBandwidthWithoutMeaning_ThenDiagnoseRefusesNamingTheOption) {
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--alpha", "1e-300"}, {"--alpha", "1"}, {"--bandwidth", "1e-9"}}) {
    const auto r = run_ldv({"diagnose", "--kfgins-config", "/nonexistent.yaml", option, value});
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << option << " " << value << ": " << r.output;
  }
}

TEST(CliFaults, GivenASolutionRowAtLatitude1e308_ThenCompareNamesTheLineInsteadOfPrintingInf) {
  const fs::path dir = temp_dir("compare_lat");
  std::string rows;
  char b[200];
  for (int k = 0; k < 20; ++k) {
    std::snprintf(b, sizeof b, "2300 %.3f %s 114.3 20.0 0 0 0 0 0 0\n", 1000.0 + k, k == 10 ? "1e308" : "30.5");
    rows += b;
  }
  std::ofstream(dir / "a.nav") << rows;
  std::string truth;
  for (int k = 0; k < 20; ++k) {
    std::snprintf(b, sizeof b, "2300 %.3f 30.5 114.3 20.0 0 0 0 0 0 0\n", 1000.0 + k);
    truth += b;
  }
  std::ofstream(dir / "b.nav") << truth;
  const auto r = run_ldv({"compare", (dir / "a.nav").string(), (dir / "b.nav").string()});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("a.nav:11: column 3: expected a latitude"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("inf"), std::string::npos) << r.output;
}

TEST(CliFaults, GivenAFifoWithNoReaderAsOutput_ThenNavFailsAtOnceNamingIt) {
  const fs::path dir = temp_dir("nav_fifo");
  simulated_files(dir, 30.0);
  const fs::path fifo = dir / "out.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const auto r = run_ldv({"nav", "--kfgins-config", (dir / "sim" / "kfgins.yaml").string(), "--out", fifo.string()},
                         30.0);
  EXPECT_FALSE(r.timed_out) << "hung on the FIFO";
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("a FIFO that nothing reads"), std::string::npos) << r.output;
}

// `ldv drive --imu-link PATH` deleted a regular file (or an empty folder) already at PATH to put its link there,
// and took one path for both links (issue 46: nothing a tool links may remove what it did not create). A link
// path may hold nothing or a symbolic link (a link an earlier drive left); anything else is refused, by option.
TEST(CliFaults, GivenALinkPathHoldingAFileOrBothLinksOnOnePath_ThenDriveRefusesAndRemovesNothing) {
  const fs::path dir = temp_dir("drive_links");
  simulated_files(dir, 5.0);
  const fs::path user_file = dir / "notes.txt", empty_folder = dir / "folder";
  std::ofstream(user_file) << "the user's own file\n";
  fs::create_directories(empty_folder);
  const std::string sim_dir = (dir / "sim").string(), free_path = (dir / "gnss_tty").string();

  const auto on_file =
      run_ldv({"drive", sim_dir, "--imu-link", user_file.string(), "--gnss-link", free_path, "--start-delay", "0"});
  EXPECT_NE(on_file.exit_code, 0) << on_file.output;
  EXPECT_NE(on_file.output.find("--imu-link"), std::string::npos) << on_file.output;
  EXPECT_TRUE(fs::is_regular_file(user_file)) << "the user's file was removed";
  EXPECT_FALSE(fs::exists(fs::symlink_status(free_path))) << "a link was left behind";

  const auto on_folder =
      run_ldv({"drive", sim_dir, "--imu-link", free_path, "--gnss-link", empty_folder.string(), "--start-delay", "0"});
  EXPECT_NE(on_folder.exit_code, 0) << on_folder.output;
  EXPECT_NE(on_folder.output.find("--gnss-link"), std::string::npos) << on_folder.output;
  EXPECT_TRUE(fs::is_directory(empty_folder)) << "the user's folder was removed";

  const auto same = run_ldv({"drive", sim_dir, "--imu-link", free_path, "--gnss-link",
                             (dir / "." / "gnss_tty").string(), "--start-delay", "0"});
  EXPECT_NE(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("same path"), std::string::npos) << same.output;
}

// `ldv smooth --out newdir/sm.nav` failed with "newdir/sm_forward.nav: cannot open file for writing", a file the
// user never named (issue 46, item 5): `nav` and `smooth` create the folder of --out as `sim` and `report` do.
TEST(CliFaults, GivenAnOutPathInAFolderNotYetMade_ThenNavAndSmoothCreateIt) {
  const fs::path dir = temp_dir("out_folder");
  const std::string config = (simulated_files(dir, 30.0) / "kfgins.yaml").string();
  for (const char* command : {"nav", "smooth"}) {
    const fs::path out = dir / (std::string("new_") + command) / "deeper" / "solution.nav";
    const auto r = run_ldv({command, "--kfgins-config", config, "--out", out.string(), "--quiet"}, 120.0);
    EXPECT_EQ(r.exit_code, 0) << command << ": " << r.output;
    EXPECT_TRUE(fs::is_regular_file(out)) << command;
  }
}

// Issue 46, item 5: `ldv help` said "A subcommand is required", and exit codes for errors varied (1, 2, 105, 106)
// with no table. `ldv help [COMMAND]` prints the help; the codes are one table for every command: 0 done, 1 the
// work failed, 2 the input was refused, 64 the command line is wrong.
TEST(CliFaults, GivenHelpAndEachKindOfError_ThenTheHelpIsPrintedAndTheExitCodeSaysWhichKind) {
  const auto help = run_ldv({"help"});
  EXPECT_EQ(help.exit_code, 0) << help.output;
  for (const char* command : {"nav", "smooth", "diagnose", "allan", "outage", "export"})
    EXPECT_NE(help.output.find(command), std::string::npos) << command << " missing from: " << help.output;
  const auto help_nav = run_ldv({"help", "nav"});
  EXPECT_EQ(help_nav.exit_code, 0) << help_nav.output;
  EXPECT_NE(help_nav.output.find("--kfgins-config"), std::string::npos) << help_nav.output;
  EXPECT_EQ(run_ldv({"help", "no_such_command"}).exit_code, 64);
  EXPECT_EQ(run_ldv({}).exit_code, 64);
  EXPECT_EQ(run_ldv({"nav", "--no-such-option"}).exit_code, 64);
  EXPECT_EQ(run_ldv({"drive"}).exit_code, 64);  // its required argument (the sim folder) missing
  const auto refused = run_ldv({"nav", "--kfgins-config", "/nonexistent/kfgins.yaml"});
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_EQ(run_ldv({"--version"}).exit_code, 0);
}

// Issue 46, item 4: a NUL inside a path of a KF-GINS configuration was untested. A YAML "\0" in imupath is refused
// by key and line (the C file API would open the path cut at the NUL: another file than the user named).
TEST(CliFaults, GivenANulInsideAConfiguredPath_ThenNavRefusesNamingTheKeyAndLine) {
  const fs::path sim_dir = simulated_files(temp_dir("nul_path"), 10.0);
  const fs::path config = sim_dir / "kfgins_nul.yaml";
  {
    std::ifstream in(sim_dir / "kfgins.yaml");
    std::ofstream out(config);
    for (std::string line; std::getline(in, line);)
      out << (line.rfind("imupath:", 0) == 0 ? "imupath: \"" + (sim_dir / "imu\\0.txt").string() + "\"" : line) << "\n";
  }
  const auto r = run_ldv({"nav", "--kfgins-config", config.string(), "--out", (sim_dir / "nul.nav").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("key 'imupath': expected a path string without a NUL character"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(config.string() + ":"), std::string::npos) << r.output;
}

}  // namespace ldv

namespace ldv::test {
namespace {
// Issue 46 (6): a time_offset estimate that steps back (--add time_offset on a drive whose IMU runs 100 ms late,
// the latency not taken out first) stamped .nav rows before the row written last: 7 rows went back. A file's
// times only increase; the epochs that would go back are counted and said.
TEST(CliFaults, GivenATimeOffsetEstimateThatStepsBack_ThenTheNavTimesStillOnlyIncrease) {
  const fs::path dir = temp_dir("nav_time_offset_steps");
  const auto sim = run_ldv({"sim", "--grade", "hg1700-typical", "--duration", "300", "--gnss-rate", "5",
                            "--imu-latency", "0.1", "--out", (dir / "sim").string(), "--quiet"},
                           120.0);
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const fs::path nav = dir / "nav.nav";
  const auto r = run_ldv({"nav", "--kfgins-config", (dir / "sim" / "kfgins.yaml").string(), "--add", "time_offset",
                          "--imu-latency", "off", "--out", nav.string()},
                         120.0);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(nav);
  double week = 0, t = 0, last_t = -1e300;
  std::string rest;
  long rows = 0, back = 0;
  while (in >> week >> t && std::getline(in, rest)) {
    back += !(t > last_t);
    last_t = t;
    ++rows;
  }
  EXPECT_GT(rows, 59000);
  EXPECT_EQ(back, 0) << "rows whose time did not increase";
  if (rows < 60000) {
    EXPECT_NE(r.output.find("epochs not written"), std::string::npos) << r.output;
  }
}
}  // namespace
}  // namespace ldv::test

namespace ldv {
namespace {
// Issue 46 (6), silent drops: two logs of one drive that overlap in time (a logger restarted, two loggers) put
// their common IMU samples into imu.txt twice, in silence. One row per epoch, the repeats counted and said.
TEST(LcmLogFaults, GivenTwoOverlappingLogs_ThenExportWritesEachEpochOnceAndSaysSo) {
  const fs::path dir = temp_dir("lcmlog_overlap");
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.duration_s = 20.0;
  req.gnss_rate_hz = 5.0;
  req.start_sow_s = 345600.0;
  const sim::SimResult sim = sim::simulate(req);
  const int week = 2300;
  auto bytes = [](const auto& m) {
    std::string b(static_cast<size_t>(m.getEncodedSize()), '\0');
    m.encode(b.data(), 0, static_cast<int>(b.size()));
    return b;
  };
  // the first log holds samples [0, 3000), the second [2000, end): 1000 samples in both
  const auto write_log = [&](const fs::path& p, size_t from, size_t to) {
    std::ofstream f(p, std::ios::binary);
    int64_t n = 0;
    for (size_t i = from; i < to; ++i)
      put_event(f, n++, "IMU", bytes(message_from_imu(sim.imu[i], week, static_cast<int64_t>(i))));
  };
  write_log(dir / "a.lcmlog", 0, 3000);
  write_log(dir / "b.lcmlog", 2000, sim.imu.size());
  const auto ex =
      run_ldv({"export", (dir / "a.lcmlog").string(), (dir / "b.lcmlog").string(), "--out", (dir / "export").string()});
  ASSERT_EQ(ex.exit_code, 0) << ex.output;
  long rows = 0, back = 0;
  double last_t = -1e300;
  std::ifstream in(dir / "export" / "imu.txt");
  for (double t; in >> t;) {
    std::string rest;
    std::getline(in, rest);
    back += !(t > last_t);
    last_t = t;
    ++rows;
  }
  EXPECT_EQ(rows, static_cast<long>(sim.imu.size()));
  EXPECT_EQ(back, 0);
  EXPECT_NE(ex.output.find("1000 IMU and 0 GNSS messages repeated an epoch"), std::string::npos) << ex.output;
}
}  // namespace
}  // namespace ldv

namespace ldv {
namespace {
// Issue 46 (6): ldv report took side inputs of the wrong shape: a JSON that is another command's (or a list)
// ended in yaml-cpp's raw "bad conversion" or an empty section, and a .nav given as the std file was drawn as
// standard deviations. Each is refused naming the file and what it should be.
TEST(CliFaults, GivenReportSideInputsOfTheWrongShape_ThenEachIsRefusedNamingTheFile) {
  const fs::path dir = temp_dir("report_shapes");
  simulated_files(dir, 30.0);
  const std::string nav = (dir / "run.nav").string();
  ASSERT_EQ(run_ldv({"nav", "--kfgins-config", (dir / "sim" / "kfgins.yaml").string(), "--out", nav}).exit_code, 0);
  std::ofstream(dir / "list.json") << "[1, 2, 3]\n";
  std::ofstream(dir / "other.json") << "{\"channels\": []}\n";  // an ldv allan --json
  const std::string out = (dir / "report").string();
  const auto as_std = run_ldv({"report", "--nav", nav, "--std", nav, "--out", out});
  EXPECT_EQ(as_std.exit_code, 2) << as_std.output;
  EXPECT_NE(as_std.output.find("run.nav:1: column 4: expected a standard deviation"), std::string::npos)
      << as_std.output;
  for (const char* json : {"list.json", "other.json"}) {
    const auto r = run_ldv({"report", "--nav", nav, "--outage-json", (dir / json).string(), "--out", out});
    EXPECT_EQ(r.exit_code, 2) << json << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(json) + ": expected the JSON that `ldv outage --json` writes"),
              std::string::npos)
        << r.output;
  }
}
}  // namespace
}  // namespace ldv
