// SPDX-License-Identifier: Apache-2.0
// Text output for test images without printf: strings, characters, unsigned decimals and
// fixed-width hex, streamed to the board console (UART0 on qemu). No heap, no buffering.
//
//   console << "seq " << dec(h.seq) << " id 0x" << hex(h.id, 2) << '\n';
#pragma once

#include <cstddef>
#include <cstdint>

#include "board.hpp"

namespace palp::fw {

struct Dec {
  std::uint32_t value;
};
struct Hex {
  std::uint32_t value;
  int digits;  // 1..8, zero-padded
};
constexpr Dec dec(std::uint32_t value) { return {value}; }
constexpr Hex hex(std::uint32_t value, int digits) { return {value, digits}; }

class Console {
 public:
  Console& operator<<(const char* text) {
    std::size_t n = 0;
    while (text[n] != '\0') ++n;
    board::console_write(text, n);
    return *this;
  }
  Console& operator<<(char c) {
    board::console_write(&c, 1);
    return *this;
  }
  Console& operator<<(Dec d) {
    char buf[10];  // 4294967295
    std::size_t n = 0;
    do {
      buf[sizeof buf - 1 - n++] = static_cast<char>('0' + d.value % 10);
      d.value /= 10;
    } while (d.value != 0);
    board::console_write(buf + sizeof buf - n, n);
    return *this;
  }
  Console& operator<<(Hex h) {
    static constexpr char kDigits[] = "0123456789abcdef";
    char buf[8];
    const int n = h.digits < 1 ? 1 : (h.digits > 8 ? 8 : h.digits);
    for (int k = 0; k < n; ++k) buf[k] = kDigits[(h.value >> (4 * (n - 1 - k))) & 0xFu];
    board::console_write(buf, static_cast<std::size_t>(n));
    return *this;
  }
};

}  // namespace palp::fw
