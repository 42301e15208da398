#include "services/tspi_pub/nmea_output.hpp"

#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <span>

#include "common/logging.hpp"
#include "services/input/serial_port.hpp"

namespace ldv {

struct NmeaOutput::Destination {
  sockaddr_storage address{};
  socklen_t length = 0;
};

NmeaOutputOptions nmea_output_options(config::ConfigSection nmea) {
  using config::Range;
  NmeaOutputOptions o;
  o.serial = nmea.text("serial", o.serial);
  o.baud = static_cast<int>(nmea.integer("baud", o.baud, 1200, 4000000));
  if (!o.serial.empty() && io::baud_constant(o.baud) == 0)
    throw config::ConfigError(nmea.where("baud") + "expected a standard baud rate (9600 ... 921600), found " +
                              std::to_string(o.baud));
  o.udp = nmea.text("udp", o.udp);
  if (!o.udp.empty()) {
    const auto colon = o.udp.rfind(':');
    const std::string port = colon == std::string::npos ? "" : o.udp.substr(colon + 1);
    const bool digits = !port.empty() && port.size() <= 5 && port.find_first_not_of("0123456789") == std::string::npos;
    if (colon == 0 || !digits || std::stol(port) < 1 || std::stol(port) > 65535)
      throw config::ConfigError(nmea.where("udp") + "expected HOST:PORT (e.g. 127.0.0.1:10110), found '" + o.udp + "'");
  }
  o.rate_hz = nmea.number("rate_hz", o.rate_hz, Range::above(0.0).up_to(100.0));
  o.talker = nmea.text("talker", o.talker);
  if (o.talker.size() != 2 || !std::isupper(static_cast<unsigned char>(o.talker[0])) ||
      !std::isupper(static_cast<unsigned char>(o.talker[1])))
    throw config::ConfigError(nmea.where("talker") + "expected a two-letter NMEA talker ID (GP, GN, IN ...), found '" +
                              o.talker + "'");
  return o;
}

nmea::SolutionEpoch solution_epoch_of(const ldv_lcm::tspi_v1_t& t) {
  constexpr double kDeg = M_PI / 180.0;
  nmea::SolutionEpoch e;
  e.gps = {t.gps_week, t.gps_sow_s};
  e.pos = {t.lat_deg * kDeg, t.lon_deg * kDeg, t.height_m};
  e.vel_n_mps = Vec3(t.vel_ned_mps[0], t.vel_ned_mps[1], t.vel_ned_mps[2]);
  e.heading_rad = t.rpy_deg[2] * kDeg;
  e.pos_std_ned_m = Vec3(t.pos_std_ned_m[0], t.pos_std_ned_m[1], t.pos_std_ned_m[2]);
  using Source = nmea::SolutionEpoch::Source;
  e.source = t.quality <= 0 ? Source::kInvalid : t.quality == 1 ? Source::kInsOnly : Source::kGnssAided;
  return e;
}

NmeaOutput::NmeaOutput(NmeaOutputOptions options) : options_(std::move(options)) {
  if (!options_.serial.empty()) {
    io::SerialOptions so;
    so.device = options_.serial;
    so.baud = options_.baud;
    serial_ = std::make_unique<io::SerialPort>(so);
  }
  if (!options_.udp.empty()) {
    const auto colon = options_.udp.rfind(':');
    udp_host_ = options_.udp.substr(0, colon);
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_DGRAM;
    addrinfo* found = nullptr;
    const int rc = ::getaddrinfo(udp_host_.c_str(), options_.udp.substr(colon + 1).c_str(), &hints, &found);
    if (rc != 0 || !found)
      throw std::runtime_error("nmea.udp: cannot resolve '" + options_.udp + "': " + ::gai_strerror(rc));
    destination_ = std::make_unique<Destination>();
    std::memcpy(&destination_->address, found->ai_addr, found->ai_addrlen);
    destination_->length = found->ai_addrlen;
    ::freeaddrinfo(found);
    udp_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (udp_fd_ < 0) throw std::runtime_error(std::string("nmea.udp: socket: ") + std::strerror(errno));
  }
}

NmeaOutput::~NmeaOutput() {
  if (udp_fd_ >= 0) ::close(udp_fd_);
}

void NmeaOutput::maintain(double now_s) {
  if (serial_) serial_->maintain(now_s);
}

void NmeaOutput::send(const ldv_lcm::tspi_v1_t& t, double now_s) {
  const std::string text = nmea::solution_sentences(solution_epoch_of(t), options_.talker);
  bool dropped = false;
  if (serial_) {
    maintain(now_s);
    // What the driver did not take of the epoch before goes first; a reader that has not drained it loses this one
    // whole (never half a sentence).
    if (!serial_pending_.empty()) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(serial_pending_.data());
      serial_pending_.erase(0, serial_->write_some(std::span(p, serial_pending_.size()), now_s));
    }
    if (serial_pending_.empty() && serial_->fd() >= 0) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
      const std::size_t n = serial_->write_some(std::span(p, text.size()), now_s);
      if (n > 0)
        serial_pending_ = text.substr(n);
      else
        dropped = true;
    } else {
      dropped = true;
    }
  }
  if (udp_fd_ >= 0 && ::sendto(udp_fd_, text.data(), text.size(), MSG_DONTWAIT,
                               reinterpret_cast<const sockaddr*>(&destination_->address), destination_->length) < 0)
    dropped = true;
  ++(dropped ? dropped_ : sent_);
}

}  // namespace ldv
