// The bus logger's rotation and retention (services/runtime/log_rotation.hpp) on real files in a
// temporary directory, fed through a real LCM memq:// bus as ldv_logger is fed from udpm://.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <set>

#include "common/bus/bus.hpp"
#include "services/runtime/log_rotation.hpp"
#include "services/runtime/service_runtime.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
constexpr double kMiB = 1024.0 * 1024.0;

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("ldv_log_rotation_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    if (!::testing::Test::HasFailure()) fs::remove_all(path);
  }
};

// A bus like the vehicle's (memq:// instead of udpm://) whose every message the writer logs, as in ldv_logger.
struct LoggedBus {
  Bus bus{"memq://"};
  RotatingLogWriter& log;
  int64_t next_seq = 0;
  explicit LoggedBus(RotatingLogWriter& w) : log(w) {
    bus.subscribe_raw(".*", [this](const std::string& ch, const uint8_t* d, int n) {
      ASSERT_TRUE(log.write(ch, d, n, static_cast<int64_t>(host_time_s() * 1e6)));
    }, 100000);
  }
  // Publishes n heartbeats (~1 kB each with the padded name) and logs them.
  void publish(int n) {
    for (int i = 0; i < n; ++i) {
      ldv_lcm::service_status_t m{};
      m.seq = next_seq++;
      m.name = std::string(1000, 'x');
      ASSERT_TRUE(bus.publish("STATUS_TEST", m));
      while (bus.handle(0) > 0) {
      }
    }
  }
};

// Every heartbeat's seq in the given files, in file order.
std::vector<int64_t> logged_sequence(const std::vector<RotatingLogWriter::LogFileInfo>& files) {
  std::vector<int64_t> seqs;
  for (const auto& f : files) {
    lcm::LogFile in(f.path, "r");
    EXPECT_TRUE(in.good()) << f.path;
    while (const lcm::LogEvent* e = in.readNextEvent()) {
      ldv_lcm::service_status_t m;
      EXPECT_GE(m.decode(e->data, 0, e->datalen), 0) << f.path;
      seqs.push_back(m.seq);
    }
  }
  return seqs;
}

uint64_t total_bytes(const std::vector<RotatingLogWriter::LogFileInfo>& files) {
  uint64_t t = 0;
  for (const auto& f : files) t += f.bytes;
  return t;
}

void set_mtime(const std::string& path, double t_s) {
  timespec ts[2];
  ts[0].tv_sec = ts[1].tv_sec = static_cast<time_t>(t_s);
  ts[0].tv_nsec = ts[1].tv_nsec = 0;
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), ts, 0), 0) << path;
}
}  // namespace

TEST(LogRotation, GivenAFileSizeLimit_WhenTheBusIsLogged_ThenFilesRotateAtTheLimitAndTogetherHoldEveryMessageInOrder) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_mb = 20000 / kMiB;  // ~20 heartbeats per file
  RotatingLogWriter w(o, host_time_s);
  LoggedBus lb(w);
  lb.publish(200);
  w.flush();

  const auto files = w.files();
  ASSERT_GE(files.size(), 9u);
  EXPECT_EQ(files.back().path, w.current_path());
  EXPECT_EQ(w.rotations(), static_cast<int64_t>(files.size()) - 1);
  for (size_t i = 0; i < files.size(); ++i) {
    EXPECT_EQ(files[i].index, static_cast<int64_t>(i)) << files[i].path;
    // A file is closed at the first event past the limit: at most one event (~1.1 kB) over.
    EXPECT_LT(files[i].bytes, 20000u + 1200u) << files[i].path;
    if (i + 1 < files.size()) {
      EXPECT_GE(files[i].bytes, 20000u) << files[i].path;
    }
  }
  EXPECT_EQ(fs::path(files[0].path).filename().string().substr(0, 14), "ldvnav.000000.");
  const auto seqs = logged_sequence(files);
  ASSERT_EQ(seqs.size(), 200u);
  for (size_t i = 0; i < seqs.size(); ++i) EXPECT_EQ(seqs[i], static_cast<int64_t>(i));
}

TEST(LogRotation, GivenATotalSizeLimit_ThenTheOldestCompletedFilesAreDeletedAndTheNewestKept) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_mb = 20000 / kMiB;
  o.max_total_mb = 100000 / kMiB;  // ~5 files
  RotatingLogWriter w(o, host_time_s);
  LoggedBus lb(w);
  lb.publish(400);
  w.flush();
  w.enforce_retention();

  const auto files = w.files();
  EXPECT_GT(w.files_deleted(), 10);
  EXPECT_LE(total_bytes(files), 100000u);
  EXPECT_GE(files.size(), 3u);
  EXPECT_EQ(files.back().path, w.current_path());
  // What is left is the newest run of files, without a hole, and it ends with the last message.
  for (size_t i = 1; i < files.size(); ++i) EXPECT_EQ(files[i].index, files[i - 1].index + 1);
  const auto seqs = logged_sequence(files);
  ASSERT_FALSE(seqs.empty());
  EXPECT_EQ(seqs.back(), 399);
  for (size_t i = 1; i < seqs.size(); ++i) EXPECT_EQ(seqs[i], seqs[i - 1] + 1);
}

TEST(LogRotation, GivenFilesOlderThanTheMaximumAge_ThenTheCompletedOnesAreDeletedButNeverTheOneBeingWritten) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_mb = 20000 / kMiB;
  o.max_age_h = 1.0;
  RotatingLogWriter w(o, host_time_s);
  LoggedBus lb(w);
  lb.publish(100);
  w.flush();
  auto files = w.files();
  ASSERT_GE(files.size(), 4u);
  // Given the first two and the current file were last written 2 h ago, the others 30 min ago
  const double now = host_time_s();
  for (size_t i = 0; i < files.size(); ++i)
    set_mtime(files[i].path, i < 2 || files[i].path == w.current_path() ? now - 7200 : now - 1800);
  w.enforce_retention();
  const auto left = w.files();
  EXPECT_EQ(left.size(), files.size() - 2);
  EXPECT_EQ(left.front().index, files[2].index);
  EXPECT_TRUE(fs::exists(w.current_path())) << "the file being written was deleted";
  EXPECT_EQ(w.files_deleted(), 2);
}

TEST(LogRotation, GivenOnlyAnAgeRotationAndATotalBelowTheCurrentFile_ThenEveryOlderFileGoesAndTheCurrentOneStays) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_min = 60;  // no size limit: the current file may outgrow the total
  o.max_total_mb = 10000 / kMiB;
  double fake_now = host_time_s();
  RotatingLogWriter w(o, [&] { return fake_now; });
  LoggedBus lb(w);
  lb.publish(30);
  const std::string first = w.current_path();
  fake_now += 3601;  // the next event starts the next file
  lb.publish(30);
  w.flush();
  w.enforce_retention();
  EXPECT_FALSE(fs::exists(first));
  ASSERT_TRUE(fs::exists(w.current_path()));
  EXPECT_GT(fs::file_size(w.current_path()), 30000u);
  EXPECT_EQ(w.files().size(), 1u);
  EXPECT_EQ(w.rotations(), 1);
}

TEST(LogRotation, GivenAMinimumFreeSpaceTheDiskCannotOffer_ThenAllCompletedFilesGoButNotTheCurrentOne) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_mb = 20000 / kMiB;
  {
    RotatingLogWriter w(o, host_time_s);
    LoggedBus lb(w);
    lb.publish(100);
    ASSERT_GE(w.files().size(), 4u);
  }
  LogRotationOptions greedy = o;
  greedy.min_free_mb = 1e12;  // an exabyte free: never true
  RotatingLogWriter w2(greedy, host_time_s);  // a second start in the same directory applies it at once
  const auto left = w2.files();
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left.front().path, w2.current_path());
  EXPECT_TRUE(fs::exists(w2.current_path()));
}

TEST(LogRotation, GivenARestartInTheSameDirectory_ThenNumberingContinuesAndOtherFilesAreNeverTouched) {
  TempDir tmp;
  // Files that are not this logger's: another base name, an lcm-logger file, notes, a near-miss name
  const std::vector<std::string> foreign{"other.000000.20250101T000000Z.lcmlog", "ldvnav.lcmlog", "ldvnav.lcmlog.00", "notes.txt",
                                         "ldvnav.12.20250101T000000Z.lcmlog", "ldvnav.000001.2025.lcmlog"};
  for (const auto& f : foreign) std::ofstream(tmp.path / f) << std::string(50000, 'z');
  for (const auto& f : foreign) set_mtime((tmp.path / f).string(), host_time_s() - 1e6);
  LogRotationOptions o;
  o.path = (tmp.path / "ldvnav.lcmlog").string();
  o.max_file_mb = 20000 / kMiB;
  o.max_total_mb = 50000 / kMiB;
  o.max_age_h = 1.0;
  int64_t last_index = -1;
  {
    RotatingLogWriter w(o, host_time_s);
    LoggedBus lb(w);
    lb.publish(60);
    last_index = w.files().back().index;
  }
  RotatingLogWriter w(o, host_time_s);
  EXPECT_EQ(w.files().back().index, last_index + 1);
  EXPECT_EQ(w.files().back().path, w.current_path());
  LoggedBus lb(w);
  lb.publish(60);
  w.enforce_retention();
  for (const auto& f : foreign) EXPECT_TRUE(fs::exists(tmp.path / f)) << f << " was deleted";
  EXPECT_LE(total_bytes(w.files()), 50000u);
}

TEST(LogRotation, WithoutRotation_ThenTheOneFileIsWrittenAsLcmLoggerWouldAndRetentionIsRefused) {
  TempDir tmp;
  LogRotationOptions o;
  o.path = (tmp.path / "run.lcmlog").string();
  {
    RotatingLogWriter w(o, host_time_s);
    EXPECT_EQ(w.current_path(), o.path);
    LoggedBus lb(w);
    lb.publish(10);
  }
  EXPECT_EQ(logged_sequence({{o.path, 0, 0, 0}}).size(), 10u);
  o.max_total_mb = 100;
  EXPECT_THROW(RotatingLogWriter(o, host_time_s), std::invalid_argument);
  o.max_total_mb = 0;
  o.max_age_h = -1;
  EXPECT_THROW(RotatingLogWriter(o, host_time_s), std::invalid_argument);
  o.max_age_h = 0;
  o.max_file_mb = 512;
  o.max_total_mb = 100;
  EXPECT_THROW(RotatingLogWriter(o, host_time_s), std::invalid_argument) << "a total below one file";
}

// `ldv_logger -c '*' FILE` truncated an existing FILE to 0 bytes, then died with SIGSEGV (issue 46, data lost):
// a channel expression the bus refuses is an error before anything is opened for writing.
TEST(BusLogger, GivenAnInvalidChannelRegexAndAnExistingLog_WhenStarted_ThenItExitsWithAnErrorAndTheLogIsKept) {
  TempDir dir;
  const fs::path log = dir.path / "kept.lcmlog";
  const std::string kept(4096, 'x');
  std::ofstream(log, std::ios::binary) << kept;
  const std::string out = (dir.path / "logger.txt").string();
  const std::string cmd =
      std::string(LDV_BIN_DIR) + "/ldv_logger --lcm-url memq:// -c '*' " + log.string() + " >" + out + " 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << "ldv_logger died by a signal (status " << status << ")";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream in(log, std::ios::binary);
  const std::string now((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(now, kept) << "the existing log was changed";
  std::ifstream msg(out);
  const std::string text((std::istreambuf_iterator<char>(msg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("'*'"), std::string::npos) << text;
}
