// CRC-32 as used by every palp frame (SPEC.md §4.3): the common "CRC-32/ISO-HDLC" (zlib, PNG,
// Ethernet): polynomial 0x04C11DB7, reflected (table polynomial 0xEDB88320), init 0xFFFFFFFF,
// reflected input and output, final xor 0xFFFFFFFF. Check value: crc32("123456789") = 0xCBF43926.
//
// Two ways to the same value. crc32_update_bytewise: one 256-entry table (1 KB), a byte a step;
// the firmware's (PALP_CRC32_SLICING undefined) and every compile-time use. Slicing-by-8: eight
// tables (8 KB), eight bytes a step, about half the instructions; the host builds' at run time
// (protocol/CMakeLists.txt defines PALP_CRC32_SLICING outside the firmware scope). The golden
// vectors and tests/protocol (both forms on every length 0..300, random data) show they agree.
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>

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

// slice k maps a byte to its CRC contribution k bytes further on: t[k][n] = step(t[k - 1][n])
constexpr std::array<std::array<u32, 256>, 8> make_crc32_slices() {
  std::array<std::array<u32, 256>, 8> t{};
  t[0] = kCrc32Table;
  for (std::size_t k = 1; k < 8; ++k)
    for (std::size_t n = 0; n < 256; ++n)
      t[k][n] = (t[k - 1][n] >> 8) ^ kCrc32Table[t[k - 1][n] & 0xFFu];
  return t;
}
inline constexpr std::array<std::array<u32, 256>, 8> kCrc32Slices = make_crc32_slices();
}  // namespace detail

/// Incremental form: start with state = kCrc32Init, feed bytes, finish with crc32_final().
inline constexpr u32 kCrc32Init = 0xFFFFFFFFu;
constexpr u32 crc32_update_bytewise(u32 state, const u8* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k)
    state = detail::kCrc32Table[(state ^ data[k]) & 0xFFu] ^ (state >> 8);
  return state;
}
/// The same, eight bytes a step (slicing-by-8), the rest a byte a step.
constexpr u32 crc32_update_sliced(u32 state, const u8* data, std::size_t size) {
  const auto& t = detail::kCrc32Slices;
  auto word = [](const u8* p) {
    return static_cast<u32>(p[0]) | (static_cast<u32>(p[1]) << 8) |
           (static_cast<u32>(p[2]) << 16) | (static_cast<u32>(p[3]) << 24);
  };
  for (; size >= 8; size -= 8, data += 8) {
    const u32 lo = state ^ word(data), hi = word(data + 4);
    state = t[7][lo & 0xFFu] ^ t[6][(lo >> 8) & 0xFFu] ^ t[5][(lo >> 16) & 0xFFu] ^
            t[4][lo >> 24] ^ t[3][hi & 0xFFu] ^ t[2][(hi >> 8) & 0xFFu] ^
            t[1][(hi >> 16) & 0xFFu] ^ t[0][hi >> 24];
  }
  return crc32_update_bytewise(state, data, size);
}
constexpr u32 crc32_update(u32 state, const u8* data, std::size_t size) {
#ifdef PALP_CRC32_SLICING
  if (!std::is_constant_evaluated()) return crc32_update_sliced(state, data, size);
#endif
  return crc32_update_bytewise(state, data, size);
}
constexpr u32 crc32_update(u32 state, char c) {
  return detail::kCrc32Table[(state ^ static_cast<u8>(c)) & 0xFFu] ^ (state >> 8);
}
constexpr u32 crc32_final(u32 state) { return state ^ 0xFFFFFFFFu; }

constexpr u32 crc32(const u8* data, std::size_t size) {
  return crc32_final(crc32_update(kCrc32Init, data, size));
}

}  // namespace palp::proto
