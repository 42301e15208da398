#pragma once
// The one wrapper around LCM (DESIGN.md section 1): nothing else in ldvnav includes lcm headers.
// - subscribe<Msg>(channel, handler): typed callbacks; a message that fails to decode (wrong
//   fingerprint, truncated) is counted in malformed() and never reaches the handler or throws.
// - every subscription gets an explicit queue capacity (LCM's default of 30 silently drops).
// - SequenceTracker counts gaps in the per-publisher sequence numbers every message carries.
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "common/bus/decode_message.hpp"

namespace ldv {

class Bus {
 public:
  // url: an LCM provider URL ("udpm://239.255.76.67:7667?ttl=0", "memq://", "file://log?mode=r").
  // Empty: LCM's default (LCM_DEFAULT_URL or udpm). Throws std::runtime_error if LCM cannot start.
  explicit Bus(const std::string& url = "");
  ~Bus();
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  template <class Msg>
  bool publish(const std::string& channel, const Msg& msg) {
    return lcm_->publish(channel, &msg) == 0;
  }

  // Subscriptions take a channel expression as LCM does (POSIX extended, anchored: ^(channel)$ matches whole
  // names); one regcomp refuses throws std::invalid_argument naming it (LCM 1.3.1 would hand back a subscription
  // with no handler, and setting its queue crashed).
  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&, const std::string& channel)> handler,
                 int queue_capacity = 1000) {
    require_channel_expression(channel);
    auto sub = std::make_unique<TypedSubscription<Msg>>(std::move(handler), &malformed_);
    lcm::Subscription* s = lcm_->subscribe(channel, &TypedSubscription<Msg>::on_raw, sub.get());
    s->setQueueCapacity(queue_capacity);
    subscriptions_.push_back(std::move(sub));
  }

  // Every message on channels matching the regex, undecoded (for `ldv spy` and loggers).
  using RawHandler = std::function<void(const std::string& channel, const uint8_t* data, int size)>;
  void subscribe_raw(const std::string& channel_regex, RawHandler handler, int queue_capacity = 10000);

  // Dispatches pending messages, waiting at most timeout_ms. Returns >0 if something was handled,
  // 0 on timeout, <0 on an LCM error.
  int handle(int timeout_ms);
  int fd() const { return lcm_->getFileno(); }
  int64_t malformed() const { return malformed_; }

 private:
  struct SubscriptionBase {
    virtual ~SubscriptionBase() = default;
  };
  template <class Msg>
  struct TypedSubscription : SubscriptionBase {
    TypedSubscription(std::function<void(const Msg&, const std::string&)> h, int64_t* malformed)
        : handler(std::move(h)), malformed_count(malformed) {}
    void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      Msg msg;
      if (!decode_message(rbuf->data, static_cast<int>(rbuf->data_size), msg)) {
        ++*malformed_count;
        return;
      }
      handler(msg, channel);
    }
    std::function<void(const Msg&, const std::string&)> handler;
    int64_t* malformed_count;
  };

  struct RawSubscription : SubscriptionBase {
    explicit RawSubscription(RawHandler h) : handler(std::move(h)) {}
    void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      handler(channel, static_cast<const uint8_t*>(rbuf->data), static_cast<int>(rbuf->data_size));
    }
    RawHandler handler;
  };

  static void require_channel_expression(const std::string& channel);
  std::unique_ptr<lcm::LCM> lcm_;
  std::vector<std::unique_ptr<SubscriptionBase>> subscriptions_;
  int64_t malformed_ = 0;
};

// Counts lost messages from the sequence numbers of one publisher. A sequence number that breaks the
// order (a jump forward or back) is believed only when the next message continues from it: one corrupt
// or stray number then costs nothing, instead of a huge "loss" kept in the heartbeat for good. A confirmed
// jump back (the publisher restarted at 0) or forward by more than kMaxCountedGap is a reset, not a loss.
class SequenceTracker {
 public:
  static constexpr int64_t kMaxCountedGap = 1'000'000;  // ~30 min of a 600 Hz stream

  // Returns the number of messages found missing with this one (a gap is counted when confirmed).
  int64_t observe(int64_t seq) {
    ++received_;
    if (!has_last_) {
      has_last_ = true;
      last_ = seq;
      return 0;
    }
    if (seq == last_ + 1) {  // in order; a pending outlier was a stray number
      if (has_pending_) ++outliers_;
      has_pending_ = false;
      last_ = seq;
      return 0;
    }
    if (has_pending_ && seq == pending_ + 1) {  // the break is confirmed
      has_pending_ = false;
      const int64_t from = last_;
      last_ = seq;
      if (pending_ > from && pending_ - from - 1 <= kMaxCountedGap) {
        lost_ += pending_ - from - 1;
        return pending_ - from - 1;
      }
      ++resets_;
      return 0;
    }
    if (has_pending_) ++outliers_;  // two breaks in a row: the first was stray
    has_pending_ = true;
    pending_ = seq;
    return 0;
  }
  int64_t received() const { return received_; }
  int64_t lost() const { return lost_; }
  int64_t resets() const { return resets_; }
  int64_t outliers() const { return outliers_; }  // numbers that broke the order and were not confirmed

 private:
  bool has_last_ = false, has_pending_ = false;
  int64_t last_ = 0, pending_ = 0, received_ = 0, lost_ = 0, resets_ = 0, outliers_ = 0;
};

}  // namespace ldv
