// SPDX-License-Identifier: Apache-2.0
// Waveform primitives for the control tick: phases as u32 fractions of a turn, and sine and
// cosine from a small table with linear interpolation. Cheap enough to run hundreds of times per
// tick on a Cortex-M4F: one table lookup is ~10 instructions, no division, no libm.
//
// Phase: a u32 p is the angle p / 2^32 turns (so it wraps exactly, like the multisine phases of
// protocol/multisine.hpp). A tone of f_Hz at control rate R advances by proto::phase_increment(f,
// R) = round(f / R * 2^32) per tick (palp/protocol/program_schedule.hpp); the realised
// frequency is increment * R / 2^32, within R / 2^33 of f (2.3 uHz at 20 kHz, 4.7 uHz at
// 40 kHz). Programs compute the phase of tick k as k * increment (mod 2^32): exact, so nothing
// accumulates however long a program runs.
//
// Table: kSineTableSize = 1024 samples of one turn, each with its slope to the next sample per
// unit of the phase's low 22 bits, so a lookup is one multiply-add: 8192 bytes of const data,
// evaluated at compile time in double and rounded to float. Interpolation between two samples
// h = 2 pi / 1024 apart is off by at most h^2 / 8 = 4.71e-6 (times the amplitude), plus float
// rounding (< 2.5e-7): kSineMaxError = 5e-6 is the stated worst case. For 0.1 A that is
// 0.5 uA, far below the 0.2 mA step of the i_cmd stream channel.
#pragma once

#include <array>
#include <cstdint>

namespace palp::fw {

inline constexpr std::uint32_t kSineTableBits = 10;
inline constexpr std::uint32_t kSineTableSize = 1u << kSineTableBits;  ///< samples per turn
/// Worst-case |sin_turns(p) - sin(2 pi p / 2^32)| over every u32 phase p.
inline constexpr float kSineMaxError = 5.0e-6f;

inline constexpr std::uint32_t kQuarterTurn = 1u << 30;
inline constexpr std::uint32_t kHalfTurn = 1u << 31;

namespace detail {
inline constexpr std::uint32_t kFractionBits = 32 - kSineTableBits;
/// Sample k of the table: sin(2 pi k / kSineTableSize) and
/// (sin(2 pi (k + 1) / kSineTableSize) - sin(2 pi k / kSineTableSize)) / 2^kFractionBits.
struct SineSample {
  float value;
  float slope;
};
/// Defined in waveform.cpp, const (flash on the MCU).
extern const std::array<SineSample, kSineTableSize> kSineTable;
}  // namespace detail

/// sin(2 pi phase / 2^32), |error| <= kSineMaxError.
inline float sin_turns(std::uint32_t phase) {
  const detail::SineSample& s = detail::kSineTable[phase >> detail::kFractionBits];
  return s.value + s.slope * static_cast<float>(phase & ((1u << detail::kFractionBits) - 1u));
}

/// cos(2 pi phase / 2^32), |error| <= kSineMaxError.
inline float cos_turns(std::uint32_t phase) { return sin_turns(phase + kQuarterTurn); }

}  // namespace palp::fw
