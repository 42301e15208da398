#pragma once
// tspi_pub's NMEA 0183 output for a downstream device (a moving map, a survey logger, anything with a serial or UDP
// NMEA input): GGA, RMC, GST, VTG and HDT from each TSPI at its own rate (common/formats/nmea_solution.hpp), on a
// serial port or pty and/or as UDP datagrams (one per epoch). Never blocks: a reader that stalls loses whole epochs
// (counted), a serial device that goes away is reopened with backoff.
#include <cstdint>
#include <ldv_lcm/tspi_v1_t.hpp>
#include <memory>
#include <string>

#include "common/config/config_section.hpp"
#include "common/formats/nmea_solution.hpp"

namespace ldv::io {
class SerialPort;
}

namespace ldv {

struct NmeaOutputOptions {
  std::string serial;  // device path ("" none)
  int baud = 115200;
  std::string udp;  // "HOST:PORT" ("" none)
  double rate_hz = 1.0;
  std::string talker = "GP";
  bool enabled() const { return !serial.empty() || !udp.empty(); }
};

// The `nmea:` section of tspi_pub's configuration; errors name the file, line and key.
NmeaOutputOptions nmea_output_options(config::ConfigSection nmea);

// The solution epoch of a TSPI message (quality 0 invalid, 1 free-inertial, 2-3 aided).
nmea::SolutionEpoch solution_epoch_of(const ldv_lcm::tspi_v1_t& t);

class NmeaOutput {
 public:
  explicit NmeaOutput(NmeaOutputOptions options);  // the UDP destination is resolved here (a bad one throws)
  ~NmeaOutput();
  NmeaOutput(const NmeaOutput&) = delete;
  NmeaOutput& operator=(const NmeaOutput&) = delete;

  void send(const ldv_lcm::tspi_v1_t& t, double now_s);
  void maintain(double now_s);  // reopens the serial port when due

  std::uint64_t epochs_sent() const { return sent_; }
  std::uint64_t epochs_dropped() const { return dropped_; }

 private:
  NmeaOutputOptions options_;
  std::unique_ptr<io::SerialPort> serial_;
  std::string serial_pending_;  // the rest of an epoch the driver took only part of
  int udp_fd_ = -1;
  std::string udp_host_;
  std::uint64_t sent_ = 0, dropped_ = 0;
  struct Destination;
  std::unique_ptr<Destination> destination_;
};

}  // namespace ldv
