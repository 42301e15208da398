#include "services/imu_acq/timing/pps_label_matcher.hpp"

#include <cmath>

namespace ldv::timing {
namespace {
// Labels name whole seconds; a TIM-TP with a configured pulse offset would need that offset here.
std::int64_t total_second(const GpsTime& t) {
  return static_cast<std::int64_t>(t.week) * 604800 + std::llround(t.sow_s);
}
}  // namespace

PpsLabelMatcher::PpsLabelMatcher(EdgeHandler on_edge, PpsLabelMatcherOptions options)
    : on_edge_(std::move(on_edge)), options_(options) {}

void PpsLabelMatcher::release_edge(std::optional<std::int64_t> gps_second) {
  const std::uint64_t counter = edge_->counter;
  edge_.reset();
  if (on_edge_) on_edge_(counter, gps_second);
}

void PpsLabelMatcher::poll(double host_time_s) {
  if (edge_ && host_time_s - edge_->host_time_s > options_.max_label_delay_s) release_edge(std::nullopt);
  if (next_label_ && host_time_s - next_label_->host_time_s > options_.max_label_delay_s) next_label_.reset();
}

void PpsLabelMatcher::on_edge(std::uint64_t counter, double host_time_s) {
  poll(host_time_s);
  if (edge_) release_edge(std::nullopt);  // a second edge before any label: the first stays unlabelled
  edge_ = PendingEdge{counter, host_time_s};
  if (next_label_) {
    const std::int64_t second = next_label_->gps_second;
    next_label_.reset();
    release_edge(second);
  }
}

void PpsLabelMatcher::on_label(const gnss::PpsTimeLabel& label, double host_time_s) {
  poll(host_time_s);
  const std::int64_t second = total_second(label.pulse_time);
  if (label.refers == gnss::PpsTimeLabel::Refers::kNextPulse) {
    next_label_ = PendingLabel{second, host_time_s};
  } else if (edge_) {
    release_edge(second);
  }
}

}  // namespace ldv::timing
