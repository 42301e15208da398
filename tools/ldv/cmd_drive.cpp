// `ldv drive DIR`: the simulated vehicle's devices. Creates one pseudo-terminal for the IMU
// time-stamp unit and one for the GNSS receiver, links their device names to the paths given
// (what imu_acq and gnss_link open as serial ports), and writes the simulator's byte streams
// (imu_device.bin, gnss.nmea) into them in real time, paced by device_schedule.txt.
#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace ldv::cli {
namespace {
namespace fs = std::filesystem;

struct Pty {
  int master = -1, slave = -1;
  std::string slave_name;
};

// A link path may hold nothing, or a symbolic link (one an earlier drive left): the drive replaces only that.
// Anything else (the user's file or folder) is refused, naming the option, before anything is created.
void require_free_link_path(const std::string& option, const std::string& link_path) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(link_path, ec);
  if (st.type() == fs::file_type::not_found || fs::is_symlink(st)) return;
  throw InputError(link_path, 0,
                   option + ": the path holds a " + (fs::is_directory(st) ? "folder" : "file") +
                       " that is not a link; ldv drive puts a symbolic link to its pseudo-terminal there and removes "
                       "nothing it did not create (give a free path)");
}

Pty open_pty_linked_to(const std::string& link_path) {
  Pty p;
  char name[256] = {};
  termios raw{};
  cfmakeraw(&raw);
  if (openpty(&p.master, &p.slave, name, &raw, nullptr) != 0) throw std::runtime_error("openpty failed");
  p.slave_name = name;
  fcntl(p.master, F_SETFL, fcntl(p.master, F_GETFL) | O_NONBLOCK);
  std::error_code ec;
  fs::remove(link_path, ec);
  fs::create_symlink(p.slave_name, link_path);
  return p;
}

// At the end the link goes, if it is still the one this drive made (someone may have put another there).
void remove_own_link(const std::string& link_path, const std::string& pty_name) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(link_path, ec)) && fs::read_symlink(link_path, ec) == pty_name)
    fs::remove(link_path, ec);
}

std::vector<char> read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(p.string(), 0, "cannot open device stream");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void add_drive_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("drive", "play the simulated IMU and GNSS receiver into pseudo-terminals in real time");
  static std::string dir, imu_link = "/tmp/ldv_imu_tty", gnss_link = "/tmp/ldv_gnss_tty";
  static double speed = 1.0, start_delay_s = 1.0;
  cmd->add_option("dir", dir, "an `ldv sim` output directory (imu_device.bin, gnss.nmea, device_schedule.txt)")->required();
  cmd->add_option("--imu-link", imu_link, "path linked to the IMU pty (imu_acq's serial device)");
  cmd->add_option("--gnss-link", gnss_link, "path linked to the GNSS pty (gnss_link's serial device)");
  cmd->add_option("--speed", speed, "playback speed (1 = real time)")->check(ldv::cli::finite_positive(1e4));
  cmd->add_option("--start-delay", start_delay_s, "seconds between creating the ptys and the first byte")
      ->check(ldv::cli::finite_range(0, 3600));
  cmd->callback([] {
    require_free_link_path("--imu-link", imu_link);
    require_free_link_path("--gnss-link", gnss_link);
    if (fs::weakly_canonical(fs::absolute(imu_link)) == fs::weakly_canonical(fs::absolute(gnss_link)))
      throw InputError(imu_link, 0, "--imu-link and --gnss-link are the same path: each device needs its own link");
    const std::vector<char> streams[2] = {read_all(fs::path(dir) / "imu_device.bin"), read_all(fs::path(dir) / "gnss.nmea")};
    struct Chunk {
      double sow_s;
      int stream;
      size_t offset, length;
    };
    std::vector<Chunk> schedule;
    const std::string sched_path = (fs::path(dir) / "device_schedule.txt").string();
    read_numeric_table(sched_path, 4, 4, [&](long line, const std::vector<double>& v) {
      const int s = static_cast<int>(v[1]);
      const size_t off = static_cast<size_t>(v[2]), len = static_cast<size_t>(v[3]);
      if ((s != 0 && s != 1) || off + len > streams[s].size())
        throw InputError(sched_path, line, "chunk outside its stream (expected: sow stream(0|1) offset length)");
      schedule.push_back({v[0], s, off, len});
    });
    if (schedule.empty()) throw InputError(sched_path, 0, "empty device schedule");
    Pty ptys[2] = {open_pty_linked_to(imu_link), open_pty_linked_to(gnss_link)};
    std::fprintf(stderr, "ldv drive: IMU on %s (%s), GNSS on %s (%s), %zu chunks over %.1f s at %gx\n", imu_link.c_str(),
                 ptys[0].slave_name.c_str(), gnss_link.c_str(), ptys[1].slave_name.c_str(), schedule.size(),
                 schedule.back().sow_s - schedule.front().sow_s, speed);
    std::this_thread::sleep_for(std::chrono::duration<double>(start_delay_s));
    const auto wall0 = std::chrono::steady_clock::now();
    const double t0 = schedule.front().sow_s;
    long dropped_bytes = 0;
    for (const Chunk& c : schedule) {
      std::this_thread::sleep_until(wall0 + std::chrono::duration<double>((c.sow_s - t0) / speed));
      // A device does not wait for a slow reader: bytes that do not fit are lost (and counted).
      const ssize_t n = ::write(ptys[c.stream].master, streams[c.stream].data() + c.offset, c.length);
      if (n < static_cast<ssize_t>(c.length)) dropped_bytes += static_cast<long>(c.length) - std::max<ssize_t>(n, 0);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    std::fprintf(stderr, "ldv drive: done (%ld bytes not taken by the readers)\n", dropped_bytes);
    for (auto& p : ptys) {
      ::close(p.master);
      ::close(p.slave);
    }
    remove_own_link(imu_link, ptys[0].slave_name);
    remove_own_link(gnss_link, ptys[1].slave_name);
  });
}

const RegisterCommand kRegisterDriveCommand{"drive", &add_drive_command};

}  // namespace
}  // namespace ldv::cli
