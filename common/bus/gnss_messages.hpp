#pragma once
// Decoded solutions and PPS labels -> the bus messages gnss_link publishes.
#include <cstdint>

#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>

#include "common/formats/gnss_solution.hpp"

namespace ldv::gnss {

// pps_event_t.flags bits as gnss_link sets them on GNSS_PPS. Bit 3 is ours: the lcm type leaves
// bits above 2 free, and imu_acq's label matcher needs to know on which side of its edge a label
// arrives (TIM-TP announces the next pulse, NMEA ZDA/RMC report the last one).
constexpr std::int32_t kPpsFlagMissingPrevious = 1 << 0;
constexpr std::int32_t kPpsFlagLabelsNextPulse = 1 << 3;
// counter_raw on GNSS_PPS: the receiver side has no counter.
constexpr std::int64_t kNoCounter = -1;

ldv_lcm::gnss_solution_t to_message(const GnssSolution& s, std::int64_t seq, double host_time_s);

// previous_second: the total GPS second of the previous label (to flag a missing one), or < 0.
ldv_lcm::pps_event_t to_message(const PpsTimeLabel& label, std::int64_t seq, double host_time_s,
                                std::int64_t previous_second);

// The label carried by a GNSS_PPS message (what imu_acq does with it).
PpsTimeLabel label_from_message(const ldv_lcm::pps_event_t& m);

// Total GPS second a label names (week * 604800 + whole seconds of week).
std::int64_t label_total_second(const PpsTimeLabel& label);

}  // namespace ldv::gnss
