#pragma once
// Pairs PPS edges with the receiver's time labels using host arrival times. Both arrive at the
// host with milliseconds of jitter, but they are hundreds of milliseconds apart, so arrival order
// and a window are enough to pair them; the counter-latched edge itself stays exact. A wrong
// pairing is caught downstream by PpsTimeFit (the label disagrees with the counter).
//   next-pulse labels (u-blox TIM-TP) come before their edge: paired with the first edge that
//   arrives within max_label_delay_s after the label;
//   last-pulse labels (NMEA ZDA/RMC) come after their edge: paired with the newest edge that
//   arrived within max_label_delay_s before the label.
// Edges nobody labels are passed on unlabelled once stale (the fit infers their second).
#include <cstdint>
#include <functional>
#include <optional>

#include "common/formats/gnss_solution.hpp"

namespace ldv::timing {

struct PpsLabelMatcherOptions {
  double max_label_delay_s = 0.98;  // a TIM-TP comes just after the previous pulse
};

class PpsLabelMatcher {
 public:
  // counter of the edge, its total GPS second when labelled.
  using EdgeHandler = std::function<void(std::uint64_t counter, std::optional<std::int64_t> gps_second)>;

  explicit PpsLabelMatcher(EdgeHandler on_edge, PpsLabelMatcherOptions options = {});

  void on_edge(std::uint64_t counter, double host_time_s);
  void on_label(const gnss::PpsTimeLabel& label, double host_time_s);
  // Passes on an edge left waiting longer than max_label_delay_s (call on a timer or per event).
  void poll(double host_time_s);

 private:
  struct PendingEdge {
    std::uint64_t counter;
    double host_time_s;
  };
  struct PendingLabel {
    std::int64_t gps_second;
    double host_time_s;
  };
  void release_edge(std::optional<std::int64_t> gps_second);

  EdgeHandler on_edge_;
  PpsLabelMatcherOptions options_;
  std::optional<PendingEdge> edge_;         // waiting for a last-pulse label
  std::optional<PendingLabel> next_label_;  // waiting for its edge
};

}  // namespace ldv::timing
