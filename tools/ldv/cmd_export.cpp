// `ldv export LOG --out DIR`: an LCM log (lcm-logger) -> the interchange files: imu.txt and gnss.txt
// (KF-GINS, from IMU and GNSS_SOLUTION), nav.nav (from NAV) and tspi.nav (from TSPI), so every
// offline tool (ldv nav, diagnose, compare, report) reads what the vehicle recorded.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/decode_message.hpp"
#include "common/bus/lcm_log_reader.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/time/gps_time.hpp"
#include "tools/ldv/command_registry.hpp"

namespace ldv::cli {
namespace {
namespace fs = std::filesystem;

template <class Msg>
NavRecord nav_record_of(const Msg& m) {
  NavRecord r;
  r.week = m.gps_week;
  r.sow_s = m.gps_sow_s;
  r.pos = {m.lat_deg * kDegToRad, m.lon_deg * kDegToRad, m.height_m};
  r.vel_n_mps = Vec3(m.vel_ned_mps[0], m.vel_ned_mps[1], m.vel_ned_mps[2]);
  r.rpy_rad = Vec3(m.rpy_deg[0], m.rpy_deg[1], m.rpy_deg[2]) * kDegToRad;
  return r;
}

void add_export_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("export", "LCM log -> imu.txt, gnss.txt (KF-GINS), nav.nav, tspi.nav");
  static std::vector<std::string> logs;
  static std::string out_dir;
  cmd->add_option("logs", logs, "LCM log file(s) (e.g. the vehicle bus log and the TSPI log)")->required();
  cmd->add_option("--out", out_dir, "output directory")->required();
  cmd->callback([] {
    fs::create_directories(out_dir);
    std::vector<ImuIncrement> imu;
    std::vector<GnssFix> gnss;
    std::unique_ptr<NavWriter> nav, tspi;
    long malformed = 0, unlocked = 0, nav_n = 0, tspi_n = 0, corrupt_events = 0, rows_not_advancing = 0;
    double last_nav_t = -1e300, last_tspi_t = -1e300;
    // KF-GINS files count seconds of the first week on past 604800 after a rollover: in time order across it.
    ContinuousGpsTime gps_time;
    // A NAV or TSPI row, into its file (opened at the first), only after the row written last: a file's times only
    // increase, and overlapping logs repeat epochs already written.
    const auto write_row = [&](std::unique_ptr<NavWriter>& writer, const char* name, double& last_t, long& rows,
                               const NavRecord& r) {
      if (!writer) writer = std::make_unique<NavWriter>((fs::path(out_dir) / name).string());
      const double t = gps_time.seconds(r.week, r.sow_s);
      if (!(t > last_t)) {
        ++rows_not_advancing;
        return;
      }
      last_t = t;
      writer->write(r);
      ++rows;
    };
    for (const std::string& path : logs) {
      LcmLogReader log(path);
      LcmLogEvent ev;
      while (log.next(ev)) {
        if (ev.channel == "IMU") {
          ldv_lcm::imu_sample_t m;
          if (!decode_message(ev.data, m) || !is_valid(m)) {
            ++malformed;
            continue;
          }
          if (!has_gps_time(m)) { ++unlocked; continue; }  // stamped before imu_acq locked to PPS
          imu.push_back(imu_from_message(m));
          imu.back().t_s = gps_time.seconds(m.gps_week, m.gps_sow_s);
        } else if (ev.channel == "GNSS_SOLUTION") {
          ldv_lcm::gnss_solution_t m;
          if (!decode_message(ev.data, m) || !is_valid(m)) {
            ++malformed;
            continue;
          }
          gnss.push_back(gnss_from_message(m));
          gnss.back().t_s = gps_time.seconds(m.gps_week, m.gps_sow_s);
        } else if (ev.channel == "NAV") {
          ldv_lcm::nav_state_t m;
          if (!decode_message(ev.data, m)) {
            ++malformed;
            continue;
          }
          write_row(nav, "nav.nav", last_nav_t, nav_n, nav_record_of(m));
        } else if (ev.channel == "TSPI") {
          ldv_lcm::tspi_v1_t m;
          if (!decode_message(ev.data, m)) {
            ++malformed;
            continue;
          }
          write_row(tspi, "tspi.nav", last_tspi_t, tspi_n, nav_record_of(m));
        }
      }
      corrupt_events += log.corrupt_events() + log.truncated_events();
    }
    // The log is in arrival order; the KF-GINS files are in time order with one row per epoch.
    auto by_time = [](const auto& a, const auto& b) { return a.t_s < b.t_s; };
    std::stable_sort(imu.begin(), imu.end(), by_time);
    std::stable_sort(gnss.begin(), gnss.end(), by_time);
    // Overlapping logs (or a message logged twice) hold an epoch more than once: one row each, counted and said
    // (issue 46: duplicate IMU samples went into imu.txt in silence).
    const auto same_epoch = [](const auto& a, const auto& b) { return std::abs(a.t_s - b.t_s) < 1e-6; };  // [s]
    const size_t imu_read = imu.size(), gnss_read = gnss.size();
    imu.erase(std::unique(imu.begin(), imu.end(), same_epoch), imu.end());
    gnss.erase(std::unique(gnss.begin(), gnss.end(), same_epoch), gnss.end());
    if (imu.size() < imu_read || gnss.size() < gnss_read)
      std::fprintf(stderr,
                   "ldv export: %zu IMU and %zu GNSS messages repeated an epoch already read (overlapping "
                   "logs?): one row each written\n",
                   imu_read - imu.size(), gnss_read - gnss.size());
    // The KF-GINS IMU file has no interval column: a reader takes the time difference as the interval,
    // so a lost sample would stretch its successor's increment over the gap. Bridge each gap with the
    // successor's rates (counted and reported) so the file's increments cover time without holes.
    long bridged = 0;
    std::vector<ImuIncrement> filled;
    filled.reserve(imu.size());
    for (const ImuIncrement& s : imu) {
      if (!filled.empty() && s.dt_s > 0) {
        const int missing = static_cast<int>(std::lround((s.t_s - filled.back().t_s) / s.dt_s)) - 1;
        for (int k = 1; k <= missing && missing < 1000; ++k, ++bridged) {
          ImuIncrement b = s;
          b.t_s = filled.back().t_s + s.dt_s;
          filled.push_back(b);
        }
      }
      filled.push_back(s);
    }
    imu.swap(filled);
    if (bridged > 0) std::fprintf(stderr, "ldv export: %ld lost IMU samples bridged with their successor's rates\n", bridged);
    if (rows_not_advancing > 0)
      std::fprintf(stderr,
                   "ldv export: %ld NAV/TSPI messages not after the row written before them (overlapping logs?): "
                   "not written, the files' times only increase\n",
                   rows_not_advancing);
    if (!imu.empty()) write_kfgins_imu((fs::path(out_dir) / "imu.txt").string(), imu);
    // 13 columns only when every fix has a velocity: a fix without one has no velocity std to write (a 0 there
    // made `ldv nav` drop every line as "std not positive").
    const bool all_with_velocity =
        std::all_of(gnss.begin(), gnss.end(), [](const GnssFix& g) { return g.has_velocity; });
    if (!gnss.empty()) write_kfgins_gnss((fs::path(out_dir) / "gnss.txt").string(), gnss, all_with_velocity);
    std::fprintf(stderr,
                 "ldv export: %zu IMU, %zu GNSS, %ld NAV, %ld TSPI records (%ld malformed messages, %ld corrupt log "
                 "events skipped, %ld IMU stamped before the PPS lock skipped) -> %s\n",
                 imu.size(), gnss.size(), nav_n, tspi_n, malformed, corrupt_events, unlocked, out_dir.c_str());
  });
}

const RegisterCommand kRegisterExportCommand{"export", &add_export_command};

}  // namespace
}  // namespace ldv::cli
