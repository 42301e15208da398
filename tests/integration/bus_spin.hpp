#pragma once
// Handles a test's bus until a condition holds or a timeout passes (integration tests).
#include <chrono>

#include "common/bus/bus.hpp"

namespace ldv::test {

template <class Pred>
bool spin_until(Bus& bus, Pred pred, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    bus.handle(10);
  }
  return pred();
}

}  // namespace ldv::test
