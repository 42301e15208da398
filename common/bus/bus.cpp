#include "common/bus/bus.hpp"

#include <regex.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace ldv {

Bus::Bus(const std::string& url) : lcm_(std::make_unique<lcm::LCM>(url)) {
  const std::string named = url.empty() ? std::string("default URL") : url;
  if (!lcm_->good())
    throw std::runtime_error("LCM could not start on '" + named + "' (multicast route missing? see deploy/README.md)");
  // A provider that started without a connection (tcpq:// with no server listening) has no descriptor: LCM's
  // handleTimeout would then select() on -1 and abort the process.
  if (lcm_->getFileno() < 0)
    throw std::runtime_error("LCM on '" + named + "' is not connected (no server listening there?)");
}

Bus::~Bus() = default;

void Bus::require_channel_expression(const std::string& channel) {
  // LCM's own test of an expression (lcm.c, lcm_subscribe): "^" channel "$", extended, without sub-matches.
  regex_t compiled;
  const std::string anchored = "^" + channel + "$";
  const int status = regcomp(&compiled, anchored.c_str(), REG_EXTENDED | REG_NOSUB);
  if (status == 0) {
    regfree(&compiled);
    return;
  }
  char why[256];
  regerror(status, &compiled, why, sizeof why);
  throw std::invalid_argument("channel expression '" + channel + "' is not a POSIX extended regular expression (" +
                              why + "); e.g. IMU, (IMU|GNSS_SOLUTION), STATUS_.*");
}

void Bus::subscribe_raw(const std::string& channel_regex, RawHandler handler, int queue_capacity) {
  require_channel_expression(channel_regex);
  auto sub = std::make_unique<RawSubscription>(std::move(handler));
  lcm::Subscription* s = lcm_->subscribe(channel_regex, &RawSubscription::on_raw, sub.get());
  s->setQueueCapacity(queue_capacity);
  subscriptions_.push_back(std::move(sub));
}

int Bus::handle(int timeout_ms) {
  if (lcm_->getFileno() < 0) {  // the connection went away: never select() on -1 (an abort)
    std::this_thread::sleep_for(std::chrono::milliseconds(std::max(0, timeout_ms)));
    return -1;
  }
  return lcm_->handleTimeout(timeout_ms);
}

}  // namespace ldv
