#pragma once
// Streaming NMEA 0183 framer: bytes in any chunking -> one callback per sentence whose checksum
// is right. Survives garbage (including binary protocols sharing the port), truncation and bad
// checksums, and counts each.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace ldv::gnss {

struct NmeaFramerCounters {
  std::uint64_t sentences = 0;      // delivered (checksum right)
  std::uint64_t bad_checksum = 0;   // complete sentence, checksum wrong
  std::uint64_t truncated = 0;      // a '$' started a sentence that never completed
  std::uint64_t overlong = 0;       // longer than max_sentence_chars: dropped
  std::uint64_t garbage_bytes = 0;  // bytes outside any sentence (line ends excluded)
};

struct NmeaFramerOptions {
  // NMEA says 82 chars, but high-precision receivers (u-blox HP, RTKLIB) print longer GGA lines.
  std::size_t max_sentence_chars = 160;
  // Sentences without "*hh": 0183 makes the checksum mandatory for these sentences; old devices
  // omit it. When false they are delivered unchecked.
  bool require_checksum = true;
};

class NmeaFramer {
 public:
  // Receives the text between '$' and '*' (e.g. "GPGGA,123519,..."), already checksum-verified.
  using SentenceHandler = std::function<void(std::string_view sentence)>;

  explicit NmeaFramer(SentenceHandler on_sentence, NmeaFramerOptions options = {});

  void feed(std::span<const std::uint8_t> bytes);
  void feed(std::string_view text);
  const NmeaFramerCounters& counters() const { return counters_; }

 private:
  enum class State { kHunt, kBody, kChecksumHigh, kChecksumLow };
  void on_byte(std::uint8_t b);
  void start_sentence();
  void finish(bool checksum_present);

  SentenceHandler on_sentence_;
  NmeaFramerOptions options_;
  NmeaFramerCounters counters_;
  State state_ = State::kHunt;
  std::string body_;
  std::uint8_t running_xor_ = 0;
  std::uint8_t received_checksum_ = 0;
};

// XOR of the characters between '$' and '*'.
std::uint8_t nmea_checksum(std::string_view body);

}  // namespace ldv::gnss
