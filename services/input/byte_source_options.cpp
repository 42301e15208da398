#include "services/input/byte_source_options.hpp"

#include <stdexcept>

namespace ldv::io {

ByteSourceOptions byte_source_options_from_yaml(const YAML::Node& input, const std::string& where) {
  ByteSourceOptions o;
  if (!input) return o;
  if (input["type"]) o.type = input["type"].as<std::string>();
  if (const auto s = input["serial"]) {
    if (s["device"]) o.serial.device = s["device"].as<std::string>();
    if (s["baud"]) o.serial.baud = s["baud"].as<int>();
    if (s["reopen_min_s"]) o.serial.reopen_min_s = s["reopen_min_s"].as<double>();
    if (s["reopen_max_s"]) o.serial.reopen_max_s = s["reopen_max_s"].as<double>();
  }
  if (const auto t = input["tcp"]) {
    if (t["host"]) o.tcp.host = t["host"].as<std::string>();
    if (t["port"]) o.tcp.port = t["port"].as<int>();
    if (t["reconnect_min_s"]) o.tcp.reconnect_min_s = t["reconnect_min_s"].as<double>();
    if (t["reconnect_max_s"]) o.tcp.reconnect_max_s = t["reconnect_max_s"].as<double>();
  }
  if (const auto f = input["file"]) {
    if (f["path"]) o.file_path = f["path"].as<std::string>();
    if (f["speed_factor"]) o.file_speed_factor = f["speed_factor"].as<double>();
  }
  if (o.type != "serial" && o.type != "tcp" && o.type != "file")
    throw std::runtime_error(where + ": input.type must be serial, tcp or file, not '" + o.type + "'");
  if (o.type == "serial" && baud_constant(o.serial.baud) == 0)
    throw std::runtime_error(where + ": input.serial.baud " + std::to_string(o.serial.baud) + " is not a standard rate");
  if (o.type == "tcp" && (o.tcp.port <= 0 || o.tcp.port > 65535))
    throw std::runtime_error(where + ": input.tcp.port must be in [1, 65535]");
  if (o.type == "file" && o.file_path.empty()) throw std::runtime_error(where + ": input.file.path is empty");
  if (o.file_speed_factor < 0) throw std::runtime_error(where + ": input.file.speed_factor must be >= 0");
  return o;
}

std::unique_ptr<ByteSource> make_byte_source(const ByteSourceOptions& o) {
  if (o.type == "tcp") return std::make_unique<TcpClient>(o.tcp);
  if (o.type == "file") return std::make_unique<FileSource>(o.file_path);
  return std::make_unique<SerialPort>(o.serial);
}

}  // namespace ldv::io
