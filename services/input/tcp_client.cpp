#include "services/input/tcp_client.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/logging.hpp"

namespace ldv::io {
namespace {
constexpr double kConnectTimeout_s = 3.0;
}

TcpClient::TcpClient(TcpClientOptions options)
    : options_(std::move(options)), backoff_(options_.reconnect_min_s, options_.reconnect_max_s) {}

TcpClient::~TcpClient() {
  if (fd_ >= 0) ::close(fd_);
}

std::string TcpClient::describe() const { return "tcp " + options_.host + ":" + std::to_string(options_.port); }

void TcpClient::maintain(double now_s) {
  if (connected_) return;
  if (fd_ >= 0) return check_connect(now_s);
  if (backoff_.due(now_s)) start_connect(now_s);
}

void TcpClient::start_connect(double now_s) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  // Numeric hosts resolve without DNS; names may block briefly, acceptable at reconnect time.
  const int rc = ::getaddrinfo(options_.host.c_str(), std::to_string(options_.port).c_str(), &hints, &found);
  if (rc != 0 || !found) {
    drop(now_s, std::string("cannot resolve: ") + ::gai_strerror(rc));
    return;
  }
  fd_ = ::socket(found->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    ::freeaddrinfo(found);
    drop(now_s, std::strerror(errno));
    return;
  }
  const int r = ::connect(fd_, found->ai_addr, found->ai_addrlen);
  ::freeaddrinfo(found);
  if (r != 0 && errno != EINPROGRESS) return drop(now_s, std::strerror(errno));
  connect_deadline_s_ = now_s + kConnectTimeout_s;
  check_connect(now_s);
}

void TcpClient::check_connect(double now_s) {
  pollfd p{fd_, POLLOUT, 0};
  if (::poll(&p, 1, 0) <= 0) {
    if (now_s > connect_deadline_s_) drop(now_s, "connect timed out");
    return;
  }
  int error = 0;
  socklen_t len = sizeof error;
  ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &len);
  if (error != 0) return drop(now_s, std::strerror(error));
  connected_ = true;
  last_error_.clear();
  ++counters_.opens;
  backoff_.succeeded();
  spdlog::info("{}: connected", describe());
}

void TcpClient::drop(double now_s, const std::string& why) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (connected_) {
    ++counters_.disconnects;
    spdlog::warn("{}: {} (reconnecting)", describe(), why);
  } else {
    ++counters_.open_failures;
    if (why != last_error_) spdlog::warn("{}: {} (retrying every {:.1f} s at most)", describe(), why, options_.reconnect_max_s);
    last_error_ = why;
  }
  connected_ = false;
  backoff_.failed(now_s);
}

std::size_t TcpClient::read_some(std::span<std::uint8_t> buffer, double now_s) {
  if (!connected_) return 0;
  const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
  if (n > 0) {
    counters_.bytes += static_cast<std::uint64_t>(n);
    return static_cast<std::size_t>(n);
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  drop(now_s, n == 0 ? "server closed the connection" : std::strerror(errno));
  return 0;
}

}  // namespace ldv::io
