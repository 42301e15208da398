#pragma once
// The `input:` section shared by the acquisition services' YAML configs:
//   input:
//     type: serial            # serial | tcp | file
//     serial: {device: /dev/ttyUSB0, baud: 115200}
//     tcp: {host: 127.0.0.1, port: 52001, reconnect_min_s: 0.5, reconnect_max_s: 10}
//     file: {path: walk.ubx, speed_factor: 1.0}   # 0: as fast as possible, 1: real time
#include <memory>
#include <string>

#include "common/config/config_section.hpp"
#include "services/input/file_source.hpp"
#include "services/input/serial_port.hpp"
#include "services/input/tcp_client.hpp"

namespace ldv::io {

struct ByteSourceOptions {
  std::string type = "serial";
  SerialOptions serial;
  TcpClientOptions tcp;
  std::string file_path;
  double file_speed_factor = 0.0;
};

// Reads the `input:` section over `defaults` (absent keys keep them). Throws config::ConfigError naming
// the file, line and key.
ByteSourceOptions byte_source_options_from(config::ConfigSection input, ByteSourceOptions defaults = {});

std::unique_ptr<ByteSource> make_byte_source(const ByteSourceOptions& o);

}  // namespace ldv::io
