#include "common/formats/nmea_framer.hpp"

namespace ldv::gnss {
namespace {
int hex_value(std::uint8_t c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}
bool printable(std::uint8_t c) { return c >= 0x20 && c <= 0x7e; }
bool line_end(std::uint8_t c) { return c == '\r' || c == '\n'; }
}  // namespace

std::uint8_t nmea_checksum(std::string_view body) {
  std::uint8_t x = 0;
  for (char c : body) x ^= static_cast<std::uint8_t>(c);
  return x;
}

NmeaFramer::NmeaFramer(SentenceHandler on_sentence, NmeaFramerOptions options)
    : on_sentence_(std::move(on_sentence)), options_(options) {
  body_.reserve(options_.max_sentence_chars);
}

void NmeaFramer::feed(std::string_view text) {
  feed(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void NmeaFramer::feed(std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) on_byte(b);
}

void NmeaFramer::start_sentence() {
  state_ = State::kBody;
  body_.clear();
  running_xor_ = 0;
}

void NmeaFramer::finish(bool checksum_present) {
  state_ = State::kHunt;
  if (checksum_present && received_checksum_ != running_xor_) {
    ++counters_.bad_checksum;
    return;
  }
  if (!checksum_present && options_.require_checksum) {
    ++counters_.truncated;
    return;
  }
  ++counters_.sentences;
  if (on_sentence_) on_sentence_(body_);
}

void NmeaFramer::on_byte(std::uint8_t b) {
  // A '$' always starts a new sentence: whatever was in progress was cut short.
  if (b == '$') {
    if (state_ != State::kHunt) ++counters_.truncated;
    start_sentence();
    return;
  }
  switch (state_) {
    case State::kHunt:
      if (!line_end(b)) ++counters_.garbage_bytes;
      return;
    case State::kBody:
      if (b == '*') {
        state_ = State::kChecksumHigh;
      } else if (line_end(b)) {
        finish(false);
      } else if (!printable(b)) {
        ++counters_.truncated;
        ++counters_.garbage_bytes;
        state_ = State::kHunt;
      } else if (body_.size() + 5 > options_.max_sentence_chars) {  // '$', '*hh' and CR LF
        ++counters_.overlong;
        state_ = State::kHunt;
      } else {
        body_.push_back(static_cast<char>(b));
        running_xor_ ^= b;
      }
      return;
    case State::kChecksumHigh:
    case State::kChecksumLow: {
      const int v = hex_value(b);
      if (v < 0) {
        ++counters_.truncated;
        if (!line_end(b)) ++counters_.garbage_bytes;
        state_ = State::kHunt;
        return;
      }
      if (state_ == State::kChecksumHigh) {
        received_checksum_ = static_cast<std::uint8_t>(v << 4);
        state_ = State::kChecksumLow;
      } else {
        received_checksum_ |= static_cast<std::uint8_t>(v);
        finish(true);  // deliver now: no need to wait for CR LF
      }
      return;
    }
  }
}

}  // namespace ldv::gnss
