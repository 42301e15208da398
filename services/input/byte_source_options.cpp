#include "services/input/byte_source_options.hpp"

#include <stdexcept>

namespace ldv::io {

ByteSourceOptions byte_source_options_from(config::ConfigSection input, ByteSourceOptions o) {
  using config::Range;
  o.type = input.choice("type", o.type, {"serial", "tcp", "file"});
  config::ConfigSection s = input.section("serial");
  o.serial.device = s.text("device", o.serial.device);
  o.serial.baud = static_cast<int>(s.integer("baud", o.serial.baud, 50, 4000000));
  o.serial.reopen_min_s = s.number("reopen_min_s", o.serial.reopen_min_s, Range::above(0.0).up_to(3600.0));
  o.serial.reopen_max_s = s.number("reopen_max_s", o.serial.reopen_max_s, Range::at_least(o.serial.reopen_min_s).up_to(3600.0));
  config::ConfigSection t = input.section("tcp");
  o.tcp.host = t.text("host", o.tcp.host);
  o.tcp.port = static_cast<int>(t.integer("port", o.tcp.port, 1, 65535));
  o.tcp.reconnect_min_s = t.number("reconnect_min_s", o.tcp.reconnect_min_s, Range::above(0.0).up_to(3600.0));
  o.tcp.reconnect_max_s =
      t.number("reconnect_max_s", o.tcp.reconnect_max_s, Range::at_least(o.tcp.reconnect_min_s).up_to(3600.0));
  config::ConfigSection f = input.section("file");
  o.file_path = f.text("path", o.file_path);
  o.file_speed_factor = f.number("speed_factor", o.file_speed_factor, Range::at_least(0.0).up_to(1e6));
  if (o.type == "serial" && baud_constant(o.serial.baud) == 0)
    s.fail("baud", "expected a standard rate (9600, 115200, 460800, ...), found " + std::to_string(o.serial.baud));
  if (o.type == "file" && o.file_path.empty()) f.fail("path", "expected a file path for input.type file");
  return o;
}

std::unique_ptr<ByteSource> make_byte_source(const ByteSourceOptions& o) {
  if (o.type == "tcp") return std::make_unique<TcpClient>(o.tcp);
  if (o.type == "file") return std::make_unique<FileSource>(o.file_path);
  return std::make_unique<SerialPort>(o.serial);
}

}  // namespace ldv::io
