#pragma once
// Decoding an LCM message: the one way it is done here (the bus's typed subscriptions, log replays, `ldv export`,
// `ldv spy`). LCM 1.3.1's generated decoders store double fields through an int64_t pointer (lcm_coretypes.h),
// against C++'s aliasing rules: inlined where the compiler knows the message's earlier value (a value-initialised
// message), GCC -O2 may keep that value, and `ldv spy` showed every decoded time and position as 0.000. The
// barrier after the decode tells the compiler memory changed, so the fields are read as the decoder stored them.
#include <cstdint>
#include <vector>

namespace ldv {

template <class Msg>
bool decode_message(const void* data, int size, Msg& m) {
  const int used = m.decode(data, 0, size);
  asm volatile("" : : "r"(&m) : "memory");
  return used >= 0;
}

template <class Msg>
bool decode_message(const std::vector<uint8_t>& bytes, Msg& m) {
  return decode_message(bytes.data(), static_cast<int>(bytes.size()), m);
}

}  // namespace ldv
