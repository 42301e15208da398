// ldv_logger: records the bus into LCM log files (the lcm-logger format, read by lcm-logplayer,
// lcm::LogFile, `ldv export`, `ldv nav --lcm-log`). Why not lcm-logger: in LCM 1.3.1 it subscribes
// with LCM's default queue of 30 messages, so a stall of a few tens of milliseconds on a loaded host
// (600 Hz IMU + 600 Hz NAV) loses messages (seen in tests/integration/test_faults.cpp), and it keeps
// no retention (a vehicle recording for weeks fills its disk). Here the subscription queue is set
// explicitly (default 200000 messages), and with --max-file-mb / --max-file-min the files rotate and
// the oldest completed ones are deleted by --max-total-mb, --max-age-h and --min-free-mb
// (log_rotation.hpp; the file being written is never deleted). It is a service like the others
// (heartbeat STATUS_LOGGER: received = events written, dropped = write errors; sd_notify), with a
// clean stop on SIGTERM/SIGINT.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <optional>

#include "common/bus/bus.hpp"
#include "common/logging.hpp"
#include "services/runtime/log_rotation.hpp"
#include "services/runtime/service_runtime.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ldv_logger: records LCM bus traffic into LCM log files with an explicit subscription queue, rotation and retention"};
  std::string url, channels = ".*";
  ldv::LogRotationOptions rot;
  int queue = 200000;
  double flush_s = 0.1, retention_check_s = 5.0;
  app.add_option("--lcm-url", url, "LCM URL of the bus");
  app.add_option("-c,--channel", channels, "channel regex");
  app.add_option("--queue", queue, "subscription queue capacity [messages]");
  app.add_option("--flush-interval", flush_s, "flush the file this often [s]");
  app.add_option("--max-file-mb", rot.max_file_mb, "rotate: start the next file at this size [MiB] (0: off)");
  app.add_option("--max-file-min", rot.max_file_min, "rotate: start the next file at this age [min] (0: off)");
  app.add_option("--max-total-mb", rot.max_total_mb, "retention: delete the oldest completed files while all exceed this [MiB] (0: off)");
  app.add_option("--max-age-h", rot.max_age_h, "retention: delete completed files last written longer ago than this [h] (0: off)");
  app.add_option("--min-free-mb", rot.min_free_mb, "retention: delete the oldest completed files while the disk has less free [MiB] (0: off)");
  app.add_option("--retention-interval", retention_check_s, "apply the retention rules this often [s]");
  app.add_option("file", rot.path,
                 "log file (overwritten) without rotation; with rotation the base path: FILE=dir/name.lcmlog writes "
                 "dir/name.NNNNNN.YYYYmmddTHHMMSSZ.lcmlog")
      ->required();
  CLI11_PARSE(app, argc, argv);
  ldv::init_logging();
  try {
    ldv::ServiceRuntime rt("logger", url);
    // Subscribed before the file is opened (which truncates it): a channel expression the bus refuses must not
    // cost the user an existing log. Nothing is dispatched before handle() below.
    std::optional<ldv::RotatingLogWriter> log;
    rt.bus().subscribe_raw(
        channels,
        [&](const std::string& channel, const uint8_t* data, int size) {
          if (log->write(channel, data, size, static_cast<int64_t>(ldv::host_time_s() * 1e6)))
            ++rt.counters().received;
          else
            ++rt.counters().dropped;
        },
        queue);
    log.emplace(rot, ldv::host_time_s);
    rt.ready();
    double next_flush = ldv::host_time_s() + flush_s, next_retention = ldv::host_time_s() + retention_check_s;
    while (rt.running()) {
      rt.bus().handle(20);
      const double now = ldv::host_time_s();
      if (now >= next_flush) {
        log->flush();
        next_flush = now + flush_s;
      }
      if (now >= next_retention) {  // ages pass and other files fill the disk without any rotation of ours
        log->enforce_retention();
        next_retention = now + retention_check_s;
      }
      rt.tick();
    }
    log->flush();
    spdlog::info("ldv_logger: stopping ({} events written, {} write errors, {} rotations, {} files deleted)",
                 rt.counters().received, rt.counters().dropped, log->rotations(), log->files_deleted());
  } catch (const std::exception& e) {
    spdlog::error("ldv_logger: {}", e.what());
    return 1;
  }
  return 0;
}
