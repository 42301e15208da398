#include "common/bus/bus.hpp"

#include <stdexcept>

namespace ldv {

Bus::Bus(const std::string& url) : lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good()) throw std::runtime_error("LCM could not start on '" + (url.empty() ? std::string("default URL") : url) + "' (multicast route missing? see deploy/README.md)");
}

Bus::~Bus() = default;

int Bus::handle(int timeout_ms) { return lcm_->handleTimeout(timeout_ms); }

}  // namespace ldv
