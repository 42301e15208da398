#include "common/bus/bus.hpp"

#include <stdexcept>

namespace ldv {

Bus::Bus(const std::string& url) : lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good()) throw std::runtime_error("LCM could not start on '" + (url.empty() ? std::string("default URL") : url) + "' (multicast route missing? see deploy/README.md)");
}

Bus::~Bus() = default;

void Bus::subscribe_raw(const std::string& channel_regex, RawHandler handler, int queue_capacity) {
  auto sub = std::make_unique<RawSubscription>(std::move(handler));
  lcm::Subscription* s = lcm_->subscribe(channel_regex, &RawSubscription::on_raw, sub.get());
  s->setQueueCapacity(queue_capacity);
  subscriptions_.push_back(std::move(sub));
}

int Bus::handle(int timeout_ms) { return lcm_->handleTimeout(timeout_ms); }

}  // namespace ldv
