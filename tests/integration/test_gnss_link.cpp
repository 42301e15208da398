// gnss_link as a real process in a private network namespace:
//  (a) the real u-blox bytes of the walk through a pty -> 536 GNSS_SOLUTION, no gaps, positions
//      equal to the protocol library's decode of the same file;
//  (b) RTKLIB's rnx2rtkp output served over TCP on 127.0.0.1 (as rtkrcv serves it) -> every
//      solution, equal to the .pos file, and a reconnect after the server drops the link;
//  (c) garbage, truncated NMEA, bad checksums and a 60 m jump: counted, rejected, still running;
//  (e) kill -9 and a fresh start on the running bus publishes again; SIGTERM exits 0.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>
#include <ldv_lcm/service_status_t.hpp>

#include "common/bus/bus.hpp"
#include "tests/integration/bus_spin.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/ubx_framer.hpp"
#include "common/formats/ubx_messages.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/integration/pty_pair.hpp"
#include "tests/services_acq/nmea_text.hpp"

using namespace ldv;

namespace {
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";
const std::string kBin = std::string(LDV_BIN_DIR) + "/gnss_link";

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))).string();
}

std::string write_config(const std::string& name, const std::string& input_yaml, const std::string& protocol) {
  const std::string path = temp_path(name) + ".yaml";
  std::ofstream(path) << "bus_url: \"" << kUrl << "\"\ninput:\n" << input_yaml << "protocol: " << protocol << "\n";
  return path;
}

// Everything gnss_link publishes, as a test sees it on the bus.
struct Listener {
  Bus bus{kUrl};
  std::vector<ldv_lcm::gnss_solution_t> solutions;
  std::vector<ldv_lcm::pps_event_t> labels;
  std::optional<ldv_lcm::service_status_t> status;
  SequenceTracker seq;
  Listener() {
    bus.subscribe<ldv_lcm::gnss_solution_t>("GNSS_SOLUTION", [this](const ldv_lcm::gnss_solution_t& m, const std::string&) {
      seq.observe(m.seq);
      solutions.push_back(m);
    }, 10000);
    bus.subscribe<ldv_lcm::pps_event_t>("GNSS_PPS", [this](const ldv_lcm::pps_event_t& m, const std::string&) { labels.push_back(m); });
    bus.subscribe<ldv_lcm::service_status_t>("STATUS_GNSS_LINK", [this](const ldv_lcm::service_status_t& m, const std::string&) { status = m; });
  }
  // Handles the bus until pred() or timeout_s.
  template <class Pred>
  bool spin_until(Pred pred, double timeout_s) {
    return test::spin_until(bus, pred, timeout_s);
  }
  void spin_for(double s) { spin_until([] { return false; }, s); }
};

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A TCP server on 127.0.0.1 (inside the namespace) with an ephemeral port.
struct TcpServer {
  int listener = -1;
  int port = 0;
  TcpServer() {
    listener = ::socket(AF_INET, SOCK_STREAM, 0);
    const int one = 1;
    ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t len = sizeof a;
    ::getsockname(listener, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
    ::listen(listener, 4);
  }
  ~TcpServer() { ::close(listener); }
};
}  // namespace

TEST(GnssLinkIntegration, GivenTheRealUbxWalkThroughAPty_ThenEverySolutionPublishedInOrderAsDecoded) {
  const auto bytes = read_bytes(std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/gnss_1730.ubx");
  ASSERT_GT(bytes.size(), 1000000u);
  // What the protocol library makes of the same bytes.
  std::vector<gnss::GnssSolution> expected;
  gnss::UbxFramer framer([&](const gnss::UbxFrame& f) {
    if (f.msg_class == gnss::kUbxClassNav && f.msg_id == gnss::kUbxIdNavPvt)
      if (auto s = gnss::solution_from_nav_pvt(*gnss::decode_nav_pvt(f.payload))) expected.push_back(*s);
  });
  framer.feed(bytes);
  ASSERT_EQ(expected.size(), 536u);

  test::PtyPair pty;
  const auto cfg = write_config("gnss_ubx", "  type: serial\n  serial: {device: " + pty.slave_path() + ", baud: 115200}\n", "ubx");
  test::ChildProcess svc(kBin, {"--config", cfg});
  Listener l;
  // Write only once the port is open: bytes buffered before the open are stale to gnss_link and dropped. Any
  // heartbeat with fault bit 0 clear says so (the port is opened before READY and the first heartbeat).
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value() && (l.status->fault_bits & 1) == 0; }, 30.0))
      << "no heartbeat";

  // Given the bytes arrive in serial-sized chunks (the pty blocks when the service falls behind)
  std::thread writer([&] {
    for (std::size_t i = 0; i < bytes.size(); i += 4096) {
      pty.write_all(bytes.data() + i, std::min<std::size_t>(4096, bytes.size() - i));
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
  });
  const bool all = l.spin_until([&] { return l.solutions.size() >= 536; }, 30.0);
  writer.join();
  l.spin_for(0.5);
  ASSERT_TRUE(all) << l.solutions.size();

  // Then 536 solutions, sequence without gaps, each equal to the library's decode
  EXPECT_EQ(l.solutions.size(), 536u);
  EXPECT_EQ(l.seq.lost(), 0);
  double max_dpos_deg = 0, max_dh = 0, max_dt = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(536, l.solutions.size()); ++i) {
    const auto& m = l.solutions[i];
    const auto& e = expected[i];
    EXPECT_EQ(m.seq, static_cast<int64_t>(i));
    EXPECT_EQ(m.gps_week, e.time.week);
    max_dt = std::max(max_dt, std::abs(m.gps_sow_s - e.time.sow_s));
    max_dpos_deg = std::max({max_dpos_deg, std::abs(m.lat_deg - e.fix.pos.lat_rad * 180 / M_PI),
                             std::abs(m.lon_deg - e.fix.pos.lon_rad * 180 / M_PI)});
    max_dh = std::max(max_dh, std::abs(m.height_m - e.fix.pos.h_m));
    EXPECT_EQ(m.fix_quality, static_cast<int>(e.fix.quality));
    EXPECT_NEAR(m.pos_cov_ned_m2[0], e.pos_cov_ned_m2(0, 0), 1e-12);
  }
  std::printf("[ ubx via pty ] published %zu, lost %lld, labels %zu, max |d lat/lon| %.3g deg, max |dh| %.3g m, "
              "max |dt| %.3g s\n",
              l.solutions.size(), static_cast<long long>(l.seq.lost()), l.labels.size(), max_dpos_deg, max_dh, max_dt);
  EXPECT_LT(max_dpos_deg, 1e-12);  // one rounding of rad -> deg
  EXPECT_EQ(max_dh, 0.0);
  EXPECT_EQ(max_dt, 0.0);
  // The heartbeat carries the counters
  l.spin_until([&] { return l.status && l.status->received > 536; }, 30.0);
  EXPECT_EQ(l.status->malformed, 0);
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
}

TEST(GnssLinkIntegration, GivenRnx2rtkpOutputServedOverTcp_ThenEverySolutionAndAReconnect) {
  const char* rnx2rtkp = "/usr/bin/rnx2rtkp";
  if (!std::filesystem::exists(rnx2rtkp)) GTEST_SKIP() << "rtklib not installed";
  const std::string d = std::string(LDV_SHARED_DATA_DIR) + "/gnss/rinex_static_septentrio/";
  const std::string conf = std::string(LDV_SOURCE_DIR) + "/deploy/rtklib/rtkrcv_instantaneous_ar.conf";
  const std::string pos = temp_path("gnss_septentrio") + ".pos";
  const std::string cmd = std::string(rnx2rtkp) + " -k " + conf + " -l 35.134707705 136.977577939 104.853 " + d +
                          "rover.obs " + d + "base.obs " + d + "base.nav -o " + pos + " 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto expected = gnss::read_rtklib_pos(pos);
  ASSERT_EQ(expected.size(), 301u);
  std::ifstream in(pos);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line + "\n");

  TcpServer server;
  const auto cfg = write_config("gnss_tcp", "  type: tcp\n  tcp: {host: 127.0.0.1, port: " + std::to_string(server.port) +
                                                ", reconnect_min_s: 0.2, reconnect_max_s: 1.0}\n", "rtklib");
  test::ChildProcess svc(kBin, {"--config", cfg});
  Listener l;
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value(); }, 30.0));

  // Given rtkrcv-like serving: header and the first half, then the server drops the client, and the
  // second half goes to the reconnected client (which joins without a header, as a late client does)
  std::atomic<bool> done{false};
  std::thread serve([&] {
    const std::size_t half = lines.size() / 2;
    for (int connection = 0; connection < 2; ++connection) {
      const int c = ::accept(server.listener, nullptr, nullptr);
      const std::size_t from = connection == 0 ? 0 : half, to = connection == 0 ? half : lines.size();
      for (std::size_t i = from; i < to; ++i) {
        if (connection == 1 && lines[i][0] == '%') continue;
        ::send(c, lines[i].data(), lines[i].size(), MSG_NOSIGNAL);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      ::close(c);
    }
    done = true;
  });
  const bool all = l.spin_until([&] { return l.solutions.size() >= expected.size(); }, 30.0);
  serve.join();
  ASSERT_TRUE(all) << l.solutions.size();
  EXPECT_EQ(l.seq.lost(), 0);
  double max_d_deg = 0, max_dh = 0;
  int fixed = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& m = l.solutions[i];
    EXPECT_NEAR(m.gps_sow_s, expected[i].time.sow_s, 1e-9);
    max_d_deg = std::max({max_d_deg, std::abs(m.lat_deg - expected[i].fix.pos.lat_rad * 180 / M_PI),
                          std::abs(m.lon_deg - expected[i].fix.pos.lon_rad * 180 / M_PI)});
    max_dh = std::max(max_dh, std::abs(m.height_m - expected[i].fix.pos.h_m));
    fixed += m.fix_quality == 1;
    EXPECT_TRUE(m.has_velocity);
  }
  std::printf("[ rnx2rtkp via tcp ] published %zu of %zu, lost %lld, fixed %d, max |d lat/lon| %.3g deg, max |dh| %.3g m\n",
              l.solutions.size(), expected.size(), static_cast<long long>(l.seq.lost()), fixed, max_d_deg, max_dh);
  EXPECT_LT(max_d_deg, 1e-12);
  EXPECT_LT(max_dh, 1e-9);
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
}

TEST(GnssLinkIntegration, GivenGarbageTruncationBadChecksumsAndAJump_ThenCountedRejectedAndStillRunning) {
  test::PtyPair pty;
  const auto cfg = write_config("gnss_bad", "  type: serial\n  serial: {device: " + pty.slave_path() + ", baud: 115200}\n", "nmea");
  test::ChildProcess svc(kBin, {"--config", cfg});
  Listener l;
  // Write only once the port is open: bytes buffered before the open are stale to gnss_link and dropped.
  // Any heartbeat with fault bit 0 clear proves the port open (it is opened, and its stale input flushed,
  // before READY and the first heartbeat): writing earlier would lose the first bytes to that flush.
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value() && (l.status->fault_bits & 1) == 0; }, 30.0));

  auto epoch = [](int k, double north_offset_m) {
    test::NmeaEpoch e;
    e.utc_seconds_of_day = 30000 + k;
    e.lat_deg = 45.0 + (k * 1.0 + north_offset_m) / 111132.0;  // 1 m/s north
    return test::nmea_epoch_text(e);
  };
  std::string stream;
  for (int k = 0; k < 5; ++k) stream += epoch(k, 0);
  std::string bad = epoch(5, 0);
  bad[10] ^= 0x01;  // a flipped bit in the GGA: bad checksum (the RMC/ZDA of the epoch survive)
  stream += bad;
  stream += std::string("\x00\xff\x13\x10\xfe garbage \x01\x02", 20);
  stream += epoch(6, 0).substr(0, 30);  // truncated GGA, cut by the next '$'
  stream += epoch(7, 0);
  stream += epoch(8, 60.0);  // a 60 m jump
  for (int k = 9; k < 14; ++k) stream += epoch(k, 0);
  for (std::size_t i = 0; i < stream.size(); i += 64) {
    pty.write_all(stream.substr(i, 64));
    l.bus.handle(2);
  }
  // Until the last good epoch is out and a heartbeat (1 Hz) has counted the faults before it; a loaded
  // machine only makes this slower
  l.spin_until([&] { return l.solutions.size() >= 11; }, 30.0);
  l.spin_until([&] { return l.status && l.status->malformed >= 3 && (l.status->fault_bits & 0xA) == 0xA; }, 30.0);

  // Then the good epochs are published, the jump is not, every fault is counted
  std::vector<int> seconds;
  for (const auto& m : l.solutions) seconds.push_back(static_cast<int>(std::lround(m.gps_sow_s)) % 60);
  std::printf("[ bad input ] published %zu solutions; heartbeat: received %lld, malformed %lld, fault bits 0x%x, state %d\n",
              l.solutions.size(), static_cast<long long>(l.status->received), static_cast<long long>(l.status->malformed),
              l.status->fault_bits, l.status->state);
  // Epochs 0-4, 7, 9-13 (5: bad GGA checksum, 6: truncated GGA, 8: the jump)
  EXPECT_EQ(l.solutions.size(), 11u);
  for (const auto& m : l.solutions) EXPECT_NE(std::lround(m.gps_sow_s) % 60, (30000 + 8 + 18) % 60);
  EXPECT_EQ(l.seq.lost(), 0);
  EXPECT_GE(l.status->malformed, 3);  // checksum + truncated + jump
  EXPECT_TRUE(l.status->fault_bits & (1 << 1)) << "jump fault bit";
  EXPECT_TRUE(l.status->fault_bits & (1 << 3)) << "bad input fault bit";
  EXPECT_EQ(l.status->state, 2);  // degraded, not dead

  // And it keeps running: a good epoch still goes through
  pty.write_all(epoch(14, 0) + epoch(15, 0));
  EXPECT_TRUE(l.spin_until([&] { return l.solutions.size() >= 12; }, 30.0));
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
}

// Issue 35, item 11: a receiver set to print GGA only (no RMC or ZDA) gives positions without a date, so no GPS
// week and no solution. gnss_link published nothing with a heartbeat of no fault; now it says why.
TEST(GnssLinkIntegration, GivenGgaWithoutAnyDate_ThenNoSolutionAndTheHeartbeatCarriesTheNoSolutionFault) {
  test::PtyPair pty;
  const auto cfg = write_config("gnss_gga_only", "  type: serial\n  serial: {device: " + pty.slave_path() + ", baud: 115200}\n", "nmea");
  test::ChildProcess svc(kBin, {"--config", cfg}, "", temp_path("gnss_gga_only") + ".log");
  Listener l;
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value() && (l.status->fault_bits & 1) == 0; }, 30.0));
  std::string stream;
  for (int k = 0; k < 20; ++k) {
    test::NmeaEpoch e;
    e.utc_seconds_of_day = 30000 + k;
    const std::string text = test::nmea_epoch_text(e);
    stream += text.substr(0, text.find("$GPRMC"));  // the GGA alone
  }
  pty.write_all(stream);
  EXPECT_TRUE(l.spin_until([&] { return l.status && (l.status->fault_bits & (1 << 4)) != 0; }, 30.0))
      << "the no-solution fault bit (4)";
  EXPECT_TRUE(l.solutions.empty());
  EXPECT_EQ(l.status->state, 2) << "degraded";
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
  std::ifstream log(svc.stderr_path());
  const std::string text{std::istreambuf_iterator<char>(log), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("no RMC or ZDA"), std::string::npos) << text;
}

// A receiver that is not plugged in: gnss_link runs (it opens the port when it appears), and its very first
// heartbeat says the input is down (it used to say "running, no fault" until the loop's first turn).
TEST(GnssLinkIntegration, GivenADeviceThatCannotBeOpened_ThenItsFirstHeartbeatSaysTheInputIsDown) {
  const auto cfg =
      write_config("gnss_unplugged", "  type: serial\n  serial: {device: /dev/ldv-no-such-tty, baud: 115200}\n", "ubx");
  Listener l;
  test::ChildProcess svc(kBin, {"--config", cfg});
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value(); }, 30.0)) << "no heartbeat";
  EXPECT_EQ(l.status->seq, 0) << "the first heartbeat was missed";
  EXPECT_EQ(l.status->fault_bits & 1, 1) << "input down";
  EXPECT_EQ(l.status->state, 2) << "degraded";
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(5.0), 0);
}

TEST(GnssLinkIntegration, GivenKill9_ThenAFreshStartOnTheRunningBusPublishesAgain) {
  const std::string file = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/gnss_1730.ubx";
  // The walk replayed from the file at 20x real time.
  const auto cfg = write_config("gnss_restart", "  type: file\n  file: {path: " + file + ", speed_factor: 20}\n", "ubx");
  Listener l;
  {
    test::ChildProcess first(kBin, {"--config", cfg});
    ASSERT_TRUE(l.spin_until([&] { return l.solutions.size() >= 20; }, 30.0));
    first.signal(SIGKILL);
    EXPECT_EQ(first.wait_exit(2.0), -SIGKILL);
  }
  const std::size_t before = l.solutions.size();
  l.spin_for(0.3);
  test::ChildProcess second(kBin, {"--config", cfg});
  ASSERT_TRUE(l.spin_until([&] { return l.solutions.size() >= before + 20; }, 30.0));
  // The restart is a new publisher: its sequence starts again at 0 (a reset, not a loss)
  EXPECT_EQ(l.solutions[before].seq, 0);
  EXPECT_EQ(l.seq.resets(), 1);
  EXPECT_EQ(l.seq.lost(), 0);
  // 20x real time: the walk's 4 Hz NAV-PVT arrive at ~80 Hz, not all at once
  const double span_s = l.solutions.back().host_time_s - l.solutions[before].host_time_s;
  const double rate_hz = (l.solutions.size() - before - 1) / span_s;
  std::printf("[ restart ] %zu before kill -9, %zu after restart, replay rate %.1f solutions/s\n", before,
              l.solutions.size() - before, rate_hz);
  EXPECT_GT(rate_hz, 20.0);
  EXPECT_LT(rate_hz, 200.0);
  second.signal(SIGTERM);
  EXPECT_EQ(second.wait_exit(3.0), 0);
}
