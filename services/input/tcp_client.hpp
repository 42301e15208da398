#pragma once
// A TCP client for a stream server such as rtkrcv's solution output (`outstr1-type=tcpsvr`) or
// str2str. Connects without blocking the service loop, and reconnects with exponential backoff
// when the server is absent or closes the connection.
#include <string>

#include "services/input/byte_source.hpp"

namespace ldv::io {

struct TcpClientOptions {
  std::string host = "127.0.0.1";
  int port = 52001;
  double reconnect_min_s = 0.5;
  double reconnect_max_s = 10.0;
};

class TcpClient : public ByteSource {
 public:
  explicit TcpClient(TcpClientOptions options);
  ~TcpClient() override;
  TcpClient(const TcpClient&) = delete;
  TcpClient& operator=(const TcpClient&) = delete;

  void maintain(double now_s) override;
  // While connecting, fd() is -1: the owner need not poll a half-open socket.
  int fd() const override { return connected_ ? fd_ : -1; }
  std::size_t read_some(std::span<std::uint8_t> buffer, double now_s) override;
  std::string describe() const override;
  bool connected() const { return connected_; }

 private:
  void start_connect(double now_s);
  void check_connect(double now_s);
  void drop(double now_s, const std::string& why);

  TcpClientOptions options_;
  ReconnectBackoff backoff_;
  int fd_ = -1;
  bool connected_ = false;
  double connect_deadline_s_ = 0.0;
  std::string last_error_;
};

}  // namespace ldv::io
