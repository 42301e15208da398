#include "services/gnss_link/gnss_stream_decoder.hpp"

#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/ubx_messages.hpp"
#include "common/logging.hpp"

namespace ldv::gnss {

std::optional<LinkProtocol> link_protocol_from_name(const std::string& name) {
  if (name == "auto") return LinkProtocol::kAuto;
  if (name == "nmea") return LinkProtocol::kNmea;
  if (name == "rtklib") return LinkProtocol::kRtklib;
  if (name == "ubx") return LinkProtocol::kUbx;
  return std::nullopt;
}

const char* link_protocol_name(LinkProtocol p) {
  switch (p) {
    case LinkProtocol::kAuto: return "auto";
    case LinkProtocol::kNmea: return "nmea";
    case LinkProtocol::kRtklib: return "rtklib";
    case LinkProtocol::kUbx: return "ubx";
  }
  return "?";
}

GnssStreamDecoder::GnssStreamDecoder(GnssDecoderOptions options, SolutionHandler on_solution, LabelHandler on_label)
    : options_(options),
      on_solution_(std::move(on_solution)),
      on_label_(std::move(on_label)),
      nmea_assembler_([this](const GnssSolution& s) { on_nmea_solution(s); },
                      [this](const PpsTimeLabel& l) { on_nmea_label(l); }, options.nmea),
      nmea_framer_([this](std::string_view s) { nmea_assembler_.on_sentence(s); }),
      ubx_framer_([this](const UbxFrame& f) { on_ubx_frame(f); }),
      rtklib_stream_([this](const GnssSolution& s) { on_rtklib_solution(s); }, options.rtklib) {
  const LinkProtocol p = options.protocol;
  feed_nmea_ = p == LinkProtocol::kNmea || p == LinkProtocol::kUbx || p == LinkProtocol::kAuto;
  feed_ubx_ = p == LinkProtocol::kUbx || p == LinkProtocol::kAuto;
  feed_rtklib_ = p == LinkProtocol::kRtklib || p == LinkProtocol::kAuto;
}

void GnssStreamDecoder::feed(std::span<const std::uint8_t> bytes) {
  if (feed_ubx_) ubx_framer_.feed(bytes);
  if (feed_nmea_) nmea_framer_.feed(bytes);
  if (feed_rtklib_) rtklib_stream_.feed(bytes);
  if (options_.protocol != LinkProtocol::kAuto || !(feed_rtklib_ && (feed_nmea_ || feed_ubx_))) return;
  // Auto: the first family to deliver a good message wins. RTKLIB text never contains '$' or a UBX
  // sync pair, and NMEA never parses as a solution line, so the first success is unambiguous.
  if (rtklib_stream_.counters().solutions + rtklib_stream_.counters().header_lines > 0) {
    feed_nmea_ = feed_ubx_ = false;
  } else if (nmea_framer_.counters().sentences + ubx_framer_.counters().frames > 0) {
    feed_rtklib_ = false;
  }
}

void GnssStreamDecoder::flush_epoch() {
  if (feed_nmea_) nmea_assembler_.flush();
}

void GnssStreamDecoder::flush_end_of_input() {
  flush_epoch();
  // Not on a quiet TCP link: half a line would be parsed, and its rest again later.
  if (feed_rtklib_) rtklib_stream_.flush();
}

void GnssStreamDecoder::on_nmea_solution(const GnssSolution& s) {
  if (nav_pvt_seen_) {
    ++duplicates_;
    return;
  }
  emit(s);
}

void GnssStreamDecoder::on_nmea_label(const PpsTimeLabel& l) {
  if (tim_tp_seen_) return;  // TIM-TP labels the same pulses with the receiver's own timing
  emit(l);
}

void GnssStreamDecoder::on_ubx_frame(const UbxFrame& f) {
  ubx_frame_seen_ = true;
  if (f.msg_class == kUbxClassNav && f.msg_id == kUbxIdNavPvt) {
    const auto pvt = decode_nav_pvt(f.payload);
    if (!pvt) return void(++ubx_undecodable_);
    nav_pvt_seen_ = true;
    // No fix yet (or no date) is a normal receiver state, not a malformed message.
    if (const auto s = solution_from_nav_pvt(*pvt)) {
      emit(*s);
    }
  } else if (f.msg_class == kUbxClassTim && f.msg_id == kUbxIdTimTp) {
    const auto tp = decode_tim_tp(f.payload);
    if (!tp) return void(++ubx_undecodable_);
    tim_tp_seen_ = true;
    if (const auto label = label_from_tim_tp(*tp)) {
      emit(*label);
    }
  }
}

void GnssStreamDecoder::on_rtklib_solution(const GnssSolution& s) {
  emit(s);
}

void GnssStreamDecoder::emit(const GnssSolution& s) {
  if (const auto why = implausibility(s)) {
    if (implausible_++ < kLoggedImplausible) spdlog::warn("gnss_link: solution dropped: {}", *why);
    return;
  }
  ++solutions_;
  on_solution_(s);
}

void GnssStreamDecoder::emit(const PpsTimeLabel& l) {
  if (const auto why = implausibility(l)) {
    if (implausible_++ < kLoggedImplausible) spdlog::warn("gnss_link: PPS label dropped: {}", *why);
    return;
  }
  ++labels_;
  if (on_label_) on_label_(l);
}

GnssDecoderCounters GnssStreamDecoder::counters() const {
  GnssDecoderCounters c;
  c.implausible = implausible_;
  c.solutions = solutions_;
  c.labels = labels_;
  c.duplicates = duplicates_;
  const NmeaFramerCounters& n = nmea_framer_.counters();
  const auto& u = ubx_framer_.counters();
  const auto& r = rtklib_stream_.counters();
  const LinkProtocol p = options_.protocol;
  // Errors count only for the protocols this link is meant to carry: on a UBX port the NMEA
  // framer also sees the binary frames, whose '$' bytes start "sentences" that never end.
  // Auto: once UBX frames appear, the NMEA framer's "truncated sentences" are '$' bytes inside
  // binary frames (also those before the first complete frame, which may retract a few counts in
  // the first chunk); only the explicit nmea protocol always counts them.
  const bool nmea_primary = feed_nmea_ && (p == LinkProtocol::kNmea || (p == LinkProtocol::kAuto && !ubx_frame_seen_));
  const bool ubx_primary = feed_ubx_ && (p == LinkProtocol::kUbx || (p == LinkProtocol::kAuto && u.frames > 0));
  const bool rtklib_primary = feed_rtklib_ && (p == LinkProtocol::kRtklib || (p == LinkProtocol::kAuto && !feed_nmea_));
  c.messages = (feed_nmea_ ? nmea_framer_.counters().sentences : 0) + (feed_ubx_ ? u.frames : 0) + (feed_rtklib_ ? r.solutions + r.header_lines : 0);
  if (nmea_primary) {
    c.bad_checksum += n.bad_checksum;
    c.truncated += n.truncated;
    c.malformed += n.overlong + nmea_assembler_.counters().malformed;
    c.epochs_without_date = nmea_assembler_.counters().epochs_without_date;
    c.garbage_bytes += n.garbage_bytes;
  }
  if (ubx_primary) {
    c.bad_checksum += u.bad_checksum;
    c.malformed += u.overlong + ubx_undecodable_;
    if (!nmea_primary) c.garbage_bytes += u.garbage_bytes;
  }
  if (rtklib_primary) c.malformed += r.malformed_lines + r.overlong_lines;
  return c;
}

std::string GnssStreamDecoder::active() const {
  if (feed_rtklib_ && !feed_nmea_ && !feed_ubx_) return "rtklib";
  if (!feed_rtklib_ || options_.protocol != LinkProtocol::kAuto) {
    if (nav_pvt_seen_ || options_.protocol == LinkProtocol::kUbx) return "ubx";
    return "nmea";
  }
  return "undecided";
}

}  // namespace ldv::gnss
