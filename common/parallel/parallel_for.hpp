#pragma once
// Runs job(i) for every index in `order` on up to `threads` threads (the calling thread included), each
// index once, taken in the given order (largest jobs first keeps the threads evenly loaded).
// When the system refuses to start another thread (a limit on tasks, memory), the work goes on with the
// threads already running instead of aborting the process; returns the number of threads that worked.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace ldv {

// More threads than this never help a CPU-bound job on one machine; a larger request is clamped.
inline constexpr int kMaxWorkerThreads = 256;

// `threads` <= 0: one per core.
inline int worker_count(int threads, size_t jobs) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int wanted = threads > 0 ? std::min(threads, kMaxWorkerThreads) : cores;
  return static_cast<int>(
      std::max<size_t>(1, std::min<size_t>(static_cast<size_t>(wanted), std::max<size_t>(jobs, 1))));
}

template <typename Job>
int parallel_for(const std::vector<size_t>& order, int threads, Job&& job) {
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k; (k = next++) < order.size();) job(order[k]);
  };
  std::vector<std::thread> pool;
  const int n = worker_count(threads, order.size());
  for (int t = 1; t < n; ++t) {
    try {
      pool.emplace_back(worker);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones running share the work
    }
  }
  worker();
  for (auto& t : pool) t.join();
  return static_cast<int>(pool.size()) + 1;
}

}  // namespace ldv
