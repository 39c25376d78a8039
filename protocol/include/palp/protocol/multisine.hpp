// SPDX-License-Identifier: Apache-2.0
// Multisine line phases (PhaseMode, SPEC.md §10 notes), defined exactly so that the device,
// which generates the waveform, and the host, which analyses it, compute the same phases bit for
// bit. Line n is line_amplitude_A * cos(2*pi*(f_n*t + phi_n)) about offset_A, f_n =
// (line_first + n*line_step) * fundamental_Hz; phi_n in turns is phase_turns / 2^32.
#pragma once

#include "palp/protocol/messages.hpp"

namespace palp::proto {

/// Marsaglia's xorshift32 (shifts 13, 17, 5). The state must not be 0.
constexpr u32 xorshift32(u32 x) {
  x ^= x << 13;
  x ^= x >> 17;
  x ^= x << 5;
  return x;
}

/// Number of excited lines of a multisine: line_first, line_first + line_step, ... <= line_last.
constexpr u32 multisine_line_count(u16 first, u16 last, u16 step) {
  if (step == 0 || last < first) return 0;
  return (static_cast<u32>(last) - first) / step + 1;
}

/// Phase of excited line n (0 for line_first) of K lines, as u32 turns.
///  random_seeded: the (n+1)-th output of xorshift32 starting from seed;
///  schroeder:     -(n+1) n / (2K) turns, reduced to [0, 1);
///  zero:          0.
/// A device computes the lines in order, so random_seeded costs one step per line.
constexpr u32 multisine_phase_turns(PhaseMode mode, u32 seed, u32 n, u32 K) {
  switch (mode) {
    case PhaseMode::random_seeded: {
      u32 x = seed == 0 ? 1u : seed;
      for (u32 k = 0; k <= n; ++k) x = xorshift32(x);
      return x;
    }
    case PhaseMode::schroeder: {
      if (K == 0) return 0;
      const u64 m = 2ull * K;
      const u64 r = (static_cast<u64>(n + 1) * n) % m;  // numerator of the turns, mod 2K
      return static_cast<u32>(((m - r) % m) * (1ull << 32) / m);
    }
    case PhaseMode::zero:
      break;
  }
  return 0;
}

}  // namespace palp::proto
