#include "common/formats/ubx_framer.hpp"

namespace ldv::gnss {
namespace {
constexpr std::uint8_t kSync1 = 0xB5, kSync2 = 0x62;
constexpr std::size_t kHeaderBytes = 6;  // sync x2, class, id, length x2
constexpr std::size_t kOverheadBytes = 8;  // header + checksum
}  // namespace

std::pair<std::uint8_t, std::uint8_t> ubx_checksum(std::span<const std::uint8_t> bytes) {
  std::uint8_t a = 0, b = 0;
  for (std::uint8_t x : bytes) {
    a = static_cast<std::uint8_t>(a + x);
    b = static_cast<std::uint8_t>(b + a);
  }
  return {a, b};
}

std::vector<std::uint8_t> ubx_encode(std::uint8_t msg_class, std::uint8_t msg_id,
                                     std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> f = {kSync1, kSync2, msg_class, msg_id, static_cast<std::uint8_t>(payload.size() & 0xff),
                                 static_cast<std::uint8_t>(payload.size() >> 8)};
  f.insert(f.end(), payload.begin(), payload.end());
  const auto [a, b] = ubx_checksum(std::span(f).subspan(2));
  f.push_back(a);
  f.push_back(b);
  return f;
}

UbxFramer::UbxFramer(FrameHandler on_frame, UbxFramerOptions options)
    : on_frame_(std::move(on_frame)), options_(options) {}

void UbxFramer::feed(std::span<const std::uint8_t> bytes) {
  pending_.insert(pending_.end(), bytes.begin(), bytes.end());
  const std::size_t n = pending_.size();
  std::size_t i = 0;
  while (i < n) {
    // Hunt: a sync pair, or a lone first sync byte at the very end (its partner may come next).
    std::size_t j = i;
    while (j < n && !(pending_[j] == kSync1 && (j + 1 == n || pending_[j + 1] == kSync2))) ++j;
    counters_.garbage_bytes += j - i;
    i = j;
    if (n - i < kHeaderBytes) break;
    const std::size_t length = pending_[i + 4] | (std::size_t{pending_[i + 5]} << 8);
    if (length > options_.max_payload_bytes) {
      ++counters_.overlong;
      i += 1;
      continue;
    }
    if (n - i < kOverheadBytes + length) break;
    const std::span<const std::uint8_t> checked(pending_.data() + i + 2, 4 + length);
    const auto [a, b] = ubx_checksum(checked);
    if (a != pending_[i + kHeaderBytes + length] || b != pending_[i + kHeaderBytes + length + 1]) {
      ++counters_.bad_checksum;
      i += 1;  // resync inside the rejected bytes
      continue;
    }
    ++counters_.frames;
    if (on_frame_) on_frame_(UbxFrame{pending_[i + 2], pending_[i + 3], checked.subspan(4)});
    i += kOverheadBytes + length;
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(i));
}

}  // namespace ldv::gnss
