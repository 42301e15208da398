#pragma once
// Streaming u-blox UBX framer: bytes in any chunking -> one callback per frame whose Fletcher
// checksum is right. Frame: 0xB5 0x62, class, id, little-endian payload length, payload, CK_A,
// CK_B (checksum over class..payload). After a bad frame it resynchronises at the next sync pair
// *inside* the rejected bytes, so a real frame hidden behind a false start is not lost.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace ldv::gnss {

struct UbxFrame {
  std::uint8_t msg_class = 0;
  std::uint8_t msg_id = 0;
  std::span<const std::uint8_t> payload;  // valid only during the callback
};

struct UbxFramerCounters {
  std::uint64_t frames = 0;         // delivered
  std::uint64_t bad_checksum = 0;   // candidate frames failing the checksum
  std::uint64_t overlong = 0;       // declared length above max_payload_bytes
  std::uint64_t garbage_bytes = 0;  // bytes skipped while hunting for a sync pair
};

struct UbxFramerOptions {
  // Largest payload accepted; RXM-RAWX with many signals reaches ~2.5 kB.
  std::size_t max_payload_bytes = 8192;
};

class UbxFramer {
 public:
  using FrameHandler = std::function<void(const UbxFrame&)>;
  explicit UbxFramer(FrameHandler on_frame, UbxFramerOptions options = {});

  void feed(std::span<const std::uint8_t> bytes);
  const UbxFramerCounters& counters() const { return counters_; }

 private:
  FrameHandler on_frame_;
  UbxFramerOptions options_;
  UbxFramerCounters counters_;
  std::vector<std::uint8_t> pending_;  // bytes not yet consumed (at most one partial frame)
};

// The two checksum bytes (CK_A, CK_B) over `bytes` (class, id, length and payload).
std::pair<std::uint8_t, std::uint8_t> ubx_checksum(std::span<const std::uint8_t> bytes);

// A complete frame (sync, header, payload, checksum) for tests and for commands to the receiver.
std::vector<std::uint8_t> ubx_encode(std::uint8_t msg_class, std::uint8_t msg_id,
                                     std::span<const std::uint8_t> payload);

}  // namespace ldv::gnss
