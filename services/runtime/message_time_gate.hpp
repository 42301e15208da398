#pragma once
// Guards a stream of time-stamped messages against one bad stamp. A message stamped more than
// max_ahead_s after the last accepted one is refused: accepted, it would carry the stream's clock far
// ahead and every good message after it would look old (fusion's NAV time froze until a restart). A real
// jump (the publisher resumed after a gap) is followed by messages that continue from the new time: after
// `confirmations` such messages in a row, each within max_ahead_s of the one before, spanning at least
// confirm_span_s of their own time, the gate moves on. The span is what tells a new time line from a burst of
// corrupted stamps: three bad stamps in a row that happen to agree (sow + 1000 s, 1000.01, 1000.02) span 20 ms
// and were taken as a jump, after which every good message looked old and the stream froze. A real jump costs
// confirm_span_s of data. Messages not after the last accepted one are refused (a stream only goes forward),
// unless the whole stream went back: a time line behind the last accepted one that holds in the same way (no
// message on the old line in between, which restarts the count) is followed too, and counted in jumps_back(),
// for the consumer to restart on (a receiver that corrected its week, a first message stamped a week ahead):
// refused for ever, it froze the consumer.
namespace ldv {

class MessageTimeGate {
 public:
  enum class Verdict { kAccepted, kTooFarAhead, kNotAfterLast };

  // min_step_s: a message closer than this after the last accepted one is the same message again (an IMU
  // sample 3 ns after another gave two NAV epochs at one printed time).
  explicit MessageTimeGate(double max_ahead_s, int confirmations = 3, double confirm_span_s = 1.0,
                           double min_step_s = 0.0)
      : max_ahead_s_(max_ahead_s), confirmations_(confirmations), confirm_span_s_(confirm_span_s),
        min_step_s_(min_step_s) {}

  // t_s: continuous time of the message (e.g. GPS week * 604800 + seconds of week).
  Verdict check(double t_s) {
    if (!has_last_) return accept(t_s);
    const bool behind = !(t_s > last_s_ + min_step_s_);
    if (!behind && t_s - last_s_ <= max_ahead_s_) return accept(t_s);
    // Off the time line, ahead or behind: does it continue a run of such messages (a new time line) or start one?
    if (run_length_ > 0 && t_s > run_last_s_ && t_s - run_last_s_ <= max_ahead_s_) {
      ++run_length_;
    } else {
      run_length_ = 1;
      run_first_s_ = t_s;
    }
    run_last_s_ = t_s;
    if (run_length_ >= confirmations_ && t_s - run_first_s_ >= confirm_span_s_) {
      ++(behind ? jumps_back_ : jumps_followed_);
      return accept(t_s);
    }
    return behind ? Verdict::kNotAfterLast : Verdict::kTooFarAhead;
  }

  bool has_accepted() const { return has_last_; }
  double last_accepted_s() const { return last_s_; }
  long jumps_followed() const { return jumps_followed_; }  // confirmed forward jumps
  long jumps_back() const { return jumps_back_; }          // confirmed backward jumps: the consumer restarts

 private:
  Verdict accept(double t_s) {
    has_last_ = true;
    last_s_ = t_s;
    run_length_ = 0;
    return Verdict::kAccepted;
  }

  double max_ahead_s_;
  int confirmations_;
  double confirm_span_s_, min_step_s_;
  bool has_last_ = false;
  double last_s_ = 0.0, run_first_s_ = 0.0, run_last_s_ = 0.0;
  int run_length_ = 0;
  long jumps_followed_ = 0, jumps_back_ = 0;
};

}  // namespace ldv
