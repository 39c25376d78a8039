// SPDX-License-Identifier: Apache-2.0
// CRC-32 as used by every palp frame (SPEC.md §4.3): the common "CRC-32/ISO-HDLC" (zlib, PNG,
// Ethernet): polynomial 0x04C11DB7, reflected (table polynomial 0xEDB88320), init 0xFFFFFFFF,
// reflected input and output, final xor 0xFFFFFFFF. Check value: crc32("123456789") = 0xCBF43926.
//
// Three ways to the same value. crc32_update_bytewise: one 256-entry table (1 KB), a byte a step;
// every compile-time use. crc32_update_sliced<N>: N tables (N KB), N bytes a step (slicing-by-N,
// N = 4 or 8), the run-time form: PALP_CRC32_SLICES picks N, 8 on hosts (protocol/CMakeLists.txt),
// 4 in the firmware, where 4 KB of flash buys a CRC in about half the instructions of the byte
// loop and 8 would add 4 KB more for little (firmware/core/README.md "Cost on the target"). The
// golden vectors and tests/protocol (every form on every length 0..300, random data) show they
// agree.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstring>
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
template <std::size_t N>
constexpr std::array<std::array<u32, 256>, N> make_crc32_slices() {
  std::array<std::array<u32, 256>, N> t{};
  t[0] = kCrc32Table;
  for (std::size_t k = 1; k < N; ++k)
    for (std::size_t n = 0; n < 256; ++n)
      t[k][n] = (t[k - 1][n] >> 8) ^ kCrc32Table[t[k - 1][n] & 0xFFu];
  return t;
}
template <std::size_t N>
inline constexpr std::array<std::array<u32, 256>, N> kCrc32Slices = make_crc32_slices<N>();
}  // namespace detail

/// Incremental form: start with state = kCrc32Init, feed bytes, finish with crc32_final().
inline constexpr u32 kCrc32Init = 0xFFFFFFFFu;
constexpr u32 crc32_update_bytewise(u32 state, const u8* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k)
    state = detail::kCrc32Table[(state ^ data[k]) & 0xFFu] ^ (state >> 8);
  return state;
}
/// The same, N bytes a step (slicing-by-N, N = 4 or 8), the rest a byte a step; it needs only
/// the N tables of slicing-by-N (the first is the byte-wise table).
template <std::size_t N>
constexpr u32 crc32_update_sliced(u32 state, const u8* data, std::size_t size) {
  static_assert(N == 4 || N == 8, "slicing-by-4 or slicing-by-8");
  const auto& t = detail::kCrc32Slices<N>;
  auto word = [](const u8* p) {
    if (!std::is_constant_evaluated() && std::endian::native == std::endian::little) {
      u32 w;  // one load where unaligned loads are allowed (the Cortex-M4's LDR is)
      std::memcpy(&w, p, sizeof w);
      return w;
    }
    return static_cast<u32>(p[0]) | (static_cast<u32>(p[1]) << 8) |
           (static_cast<u32>(p[2]) << 16) | (static_cast<u32>(p[3]) << 24);
  };
  // one pointer a table: each look-up is one load (a single base with offsets costs an add each)
  const u32 *t0 = t[0].data(), *t1 = t[1].data(), *t2 = t[2].data(), *t3 = t[3].data();
  for (; size >= N; size -= N, data += N) {
    const u32 lo = state ^ word(data);
    if constexpr (N == 4) {
      state = t3[lo & 0xFFu] ^ t2[(lo >> 8) & 0xFFu] ^ t1[(lo >> 16) & 0xFFu] ^ t0[lo >> 24];
    } else {
      const u32 hi = word(data + 4);
      state = t[7][lo & 0xFFu] ^ t[6][(lo >> 8) & 0xFFu] ^ t[5][(lo >> 16) & 0xFFu] ^
              t[4][lo >> 24] ^ t3[hi & 0xFFu] ^ t2[(hi >> 8) & 0xFFu] ^ t1[(hi >> 16) & 0xFFu] ^
              t0[hi >> 24];
    }
  }
  for (; size > 0; --size, ++data) state = t0[(state ^ *data) & 0xFFu] ^ (state >> 8);
  return state;
}
#ifndef PALP_CRC32_SLICES
#define PALP_CRC32_SLICES 4
#endif
/// Bytes a step of the run-time CRC (slicing-by-N).
inline constexpr std::size_t kCrc32SliceBytes = PALP_CRC32_SLICES;
constexpr u32 crc32_update(u32 state, const u8* data, std::size_t size) {
  if (std::is_constant_evaluated()) return crc32_update_bytewise(state, data, size);
  return crc32_update_sliced<kCrc32SliceBytes>(state, data, size);
}
constexpr u32 crc32_update(u32 state, char c) {
  return detail::kCrc32Table[(state ^ static_cast<u8>(c)) & 0xFFu] ^ (state >> 8);
}
constexpr u32 crc32_final(u32 state) { return state ^ 0xFFFFFFFFu; }

constexpr u32 crc32(const u8* data, std::size_t size) {
  return crc32_final(crc32_update(kCrc32Init, data, size));
}

}  // namespace palp::proto
