// CRC-32 as used by every palp frame (SPEC.md §4.3): the common "CRC-32/ISO-HDLC" (zlib, PNG,
// Ethernet): polynomial 0x04C11DB7, reflected (table polynomial 0xEDB88320), init 0xFFFFFFFF,
// reflected input and output, final xor 0xFFFFFFFF. Check value: crc32("123456789") = 0xCBF43926.
#pragma once

#include <array>
#include <cstddef>

#include "palp/protocol/wire_types.hpp"

namespace palp::proto {

namespace detail {
constexpr std::array<u32, 256> make_crc32_table() {
  std::array<u32, 256> t{};
  for (u32 n = 0; n < 256; ++n) {
    u32 c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
    t[n] = c;
  }
  return t;
}
inline constexpr std::array<u32, 256> kCrc32Table = make_crc32_table();
}  // namespace detail

/// Incremental form: start with state = kCrc32Init, feed bytes, finish with crc32_final().
inline constexpr u32 kCrc32Init = 0xFFFFFFFFu;
constexpr u32 crc32_update(u32 state, const u8* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k)
    state = detail::kCrc32Table[(state ^ data[k]) & 0xFFu] ^ (state >> 8);
  return state;
}
constexpr u32 crc32_update(u32 state, char c) {
  return detail::kCrc32Table[(state ^ static_cast<u8>(c)) & 0xFFu] ^ (state >> 8);
}
constexpr u32 crc32_final(u32 state) { return state ^ 0xFFFFFFFFu; }

constexpr u32 crc32(const u8* data, std::size_t size) {
  return crc32_final(crc32_update(kCrc32Init, data, size));
}

}  // namespace palp::proto
