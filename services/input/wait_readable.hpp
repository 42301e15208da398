#pragma once
// poll() on up to a few descriptors (-1 entries are skipped): which ones are readable (or hung up,
// which a read then reports). Sleeps the whole timeout when none is valid.
#include <poll.h>

#include <array>
#include <chrono>
#include <thread>

namespace ldv::io {

template <std::size_t N>
std::array<bool, N> wait_readable(const std::array<int, N>& fds, int timeout_ms) {
  std::array<pollfd, N> p{};
  std::array<bool, N> ready{};
  nfds_t n = 0;
  std::array<std::size_t, N> index{};
  for (std::size_t i = 0; i < N; ++i) {
    if (fds[i] < 0) continue;
    p[n] = pollfd{fds[i], POLLIN, 0};
    index[n++] = i;
  }
  if (n == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    return ready;
  }
  if (::poll(p.data(), n, timeout_ms) <= 0) return ready;  // timeout or EINTR (SIGTERM)
  for (nfds_t k = 0; k < n; ++k) ready[index[k]] = (p[k].revents & (POLLIN | POLLHUP | POLLERR)) != 0;
  return ready;
}

}  // namespace ldv::io
