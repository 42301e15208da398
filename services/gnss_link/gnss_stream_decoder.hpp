#pragma once
// The glue between a byte stream and the protocol library: feeds the right framers for the
// configured protocol and hands out solutions and PPS labels, with one set of counters.
//   nmea:   NMEA 0183 epochs (GGA/GST/RMC/VTG/ZDA); whole-second RMC/ZDA give last-pulse labels.
//   rtklib: the rtkrcv solution stream / .pos text.
//   ubx:    u-blox NAV-PVT solutions and TIM-TP next-pulse labels. A u-blox port also carries
//           NMEA, so the NMEA framer is fed too: its solutions are dropped as duplicates once
//           NAV-PVT flows, its labels are used until TIM-TP flows.
//   auto:   all three until one speaks; text RTKLIB and NMEA/UBX then exclude each other.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "common/formats/gnss_solution.hpp"
#include "common/formats/nmea_epoch_assembler.hpp"
#include "common/formats/nmea_framer.hpp"
#include "common/formats/rtklib_solution_stream.hpp"
#include "common/formats/ubx_framer.hpp"

namespace ldv::gnss {

enum class LinkProtocol { kAuto, kNmea, kRtklib, kUbx };
std::optional<LinkProtocol> link_protocol_from_name(const std::string& name);
const char* link_protocol_name(LinkProtocol p);

struct GnssDecoderOptions {
  LinkProtocol protocol = LinkProtocol::kAuto;
  NmeaEpochOptions nmea;
  RtklibParserOptions rtklib;
};

struct GnssDecoderCounters {
  std::uint64_t messages = 0;          // good sentences, frames and solution lines
  std::uint64_t solutions = 0;         // handed out
  std::uint64_t labels = 0;            // handed out
  std::uint64_t bad_checksum = 0;      // NMEA and UBX
  std::uint64_t truncated = 0;         // NMEA sentences that never completed
  std::uint64_t malformed = 0;         // undecodable fields / lines, overlong messages
  std::uint64_t garbage_bytes = 0;     // bytes outside any message of the active protocol(s)
  std::uint64_t duplicates = 0;        // NMEA solutions dropped because NAV-PVT gives them
  // Decoded but impossible (gnss_solution_checks.hpp: week, time of week, lat/lon/h, variances): dropped.
  std::uint64_t implausible = 0;
  // NMEA epochs with a fix but no date yet (no RMC or ZDA on the port): the GPS week is unknown, nothing published.
  std::uint64_t epochs_without_date = 0;
  std::uint64_t rejected_total() const { return bad_checksum + truncated + malformed + implausible; }
};

class GnssStreamDecoder {
 public:
  using SolutionHandler = std::function<void(const GnssSolution&)>;
  using LabelHandler = std::function<void(const PpsTimeLabel&)>;

  GnssStreamDecoder(GnssDecoderOptions options, SolutionHandler on_solution, LabelHandler on_label);

  void feed(std::span<const std::uint8_t> bytes);
  // A quiet link: emits the NMEA epoch in progress (an epoch otherwise ends when the next begins).
  void flush_epoch();
  // End of input: also parses a final RTKLIB line that has no line end.
  void flush_end_of_input();
  // Sum of every framer's counters, recomputed on each call.
  GnssDecoderCounters counters() const;
  // The protocol family in use ("nmea", "ubx", "rtklib"; "undecided" in auto until one speaks).
  std::string active() const;

 private:
  void on_nmea_solution(const GnssSolution& s);
  void on_nmea_label(const PpsTimeLabel& l);
  void on_ubx_frame(const UbxFrame& f);
  void on_rtklib_solution(const GnssSolution& s);
  // Every solution and label leaves through these: implausible ones are counted and dropped.
  void emit(const GnssSolution& s);
  void emit(const PpsTimeLabel& l);
  static constexpr std::uint64_t kLoggedImplausible = 20;  // then only counted

  GnssDecoderOptions options_;
  SolutionHandler on_solution_;
  LabelHandler on_label_;
  NmeaEpochAssembler nmea_assembler_;
  NmeaFramer nmea_framer_;
  UbxFramer ubx_framer_;
  RtklibSolutionStream rtklib_stream_;
  bool feed_nmea_, feed_ubx_, feed_rtklib_;
  bool nav_pvt_seen_ = false, tim_tp_seen_ = false;
  bool ubx_frame_seen_ = false;  // auto: the port is a u-blox one
  std::uint64_t ubx_undecodable_ = 0, duplicates_ = 0, solutions_ = 0, labels_ = 0, implausible_ = 0;
};

}  // namespace ldv::gnss
