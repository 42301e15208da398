// `ldv play DIR`: publishes a recorded or simulated run (KF-GINS imu.txt + gnss.txt) on the bus as
// imu_acq and gnss_link would: IMU at its own rate, each GNSS solution after a configurable latency,
// paced in real time (or faster with --speed). For demos and bus-level tests without devices.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/bus/bus.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/time/gps_time.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace ldv::cli {
namespace {

void add_play_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("play", "publish imu.txt + gnss.txt of a directory on the LCM bus in real time");
  static std::string dir, url;
  static double speed = 1.0, latency_s = 0.15, duration_s = 0;
  static int week = -1;
  cmd->add_option("dir", dir, "directory with imu.txt, gnss.txt (and truth.nav for the GPS week)")->required();
  cmd->add_option("--url", url, "LCM URL (default: LCM's default)");
  cmd->add_option("--speed", speed, "playback speed factor (1 = real time)")->check(ldv::cli::finite_positive(1e4));
  cmd->add_option("--gnss-latency", latency_s, "GNSS solution latency after its epoch [s]")
      ->check(ldv::cli::finite_range(0, 60));
  cmd->add_option("--duration", duration_s, "stop after this many seconds of data (0 = all)")
      ->check(ldv::cli::finite_range(0, 1e7));
  cmd->add_option("--week", week, "GPS week of the files' first second (default: from truth.nav)")
      ->check(ldv::cli::finite_range(0, 9999));
  cmd->callback([] {
    namespace fs = std::filesystem;
    const auto imu = read_kfgins_imu((fs::path(dir) / "imu.txt").string());
    const auto gnss = read_kfgins_gnss((fs::path(dir) / "gnss.txt").string());
    if (week < 0) {
      const fs::path truth = fs::path(dir) / "truth.nav";
      if (fs::exists(truth)) {
        std::ifstream in(truth);
        in >> week;
      }
      // The files hold seconds of week only; week 0 (1980) is no receiver's time and fusion refuses it.
      if (week < 0) throw InputError(dir, 0, "no GPS week: give --week (imu.txt holds seconds of week only)");
    }
    if (week < gnss::kMinPlausibleGpsWeek || week > gnss::kMaxPlausibleGpsWeek)
      throw InputError(dir, 0, "--week " + std::to_string(week) + ": expected a GPS week in [" +
                                   std::to_string(gnss::kMinPlausibleGpsWeek) + ", " +
                                   std::to_string(gnss::kMaxPlausibleGpsWeek) + "]");
    Bus bus(url);
    const double t0 = imu.front().t_s;
    const auto wall0 = std::chrono::steady_clock::now();
    auto wait_until_data_time = [&](double t) {
      const auto due = wall0 + std::chrono::duration<double>((t - t0) / speed);
      std::this_thread::sleep_until(due);
    };
    size_t g = 0;
    int64_t imu_seq = 0, gnss_seq = 0, failed = 0;
    // KF-GINS files count seconds of week on past 604800 after a rollover: on the bus, week + seconds of week.
    ContinuousGpsTime gps_time;
    gps_time.seconds(week, 0.0);
    const auto on_week = [&](auto record) {
      const GpsTime t = gps_time.week_time(record.t_s);
      record.t_s = t.sow_s;
      return std::make_pair(record, t.week);
    };
    for (const auto& s : imu) {
      if (duration_s > 0 && s.t_s - t0 > duration_s) break;
      // GNSS solutions become available latency_s after their epoch.
      while (g < gnss.size() && gnss[g].t_s + latency_s <= s.t_s) {
        wait_until_data_time(gnss[g].t_s + latency_s);
        const auto [fix, fix_week] = on_week(gnss[g]);
        failed += !bus.publish("GNSS_SOLUTION", message_from_gnss(fix, fix_week, gnss_seq++));
        ++g;
      }
      wait_until_data_time(s.t_s);
      const auto [sample, sample_week] = on_week(s);
      failed += !bus.publish("IMU", message_from_imu(sample, sample_week, imu_seq++));
    }
    if (failed > 0)
      throw std::runtime_error(std::to_string(failed) + " of " + std::to_string(imu_seq + gnss_seq) +
                               " messages could not be published on '" + url + "' (is the bus connected?)");
    std::fprintf(stderr, "ldv play: published %lld IMU samples and %lld GNSS solutions\n",
                 static_cast<long long>(imu_seq), static_cast<long long>(gnss_seq));
  });
}

const RegisterCommand kRegisterPlayCommand{"play", &add_play_command};

}  // namespace
}  // namespace ldv::cli
