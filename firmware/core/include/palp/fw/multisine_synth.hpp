// SPDX-License-Identifier: Apache-2.0
// The multisine generator: up to kMaxMultisineLines cosines summed in a bounded, constant amount
// of work per control tick.
//
// Waveform (SPEC.md §10 notes, protocol/multisine.hpp): line n of K is
// cos(2 pi (h_n t / T + phi_n)), h_n = line_first + n line_step, T the period, phi_n =
// multisine_phase_turns(...) / 2^32 turns. This class produces the unit sum
//   x(t) = sum_n cos(2 pi (h_n t / T + phi_n));  the program outputs offset_A + line_amplitude_A x.
//
// Sub-rate: summing 400 lines every tick costs ~7200 instructions (~10000 cycles), more than the
// whole tick's budget (4250 cycles = 50 % of 170 MHz / 20 kHz). So x is evaluated exactly at
// sub-rate points every D = rate / kMultisineSubRate_Hz ticks (D = 8 at 20 kHz, 16 at 40 kHz:
// 2500 points per second either way) and linearly interpolated in between. The work of a point
// is spread evenly: while the tick interpolates between points m and m+1, each of its D ticks
// sums 1/D of the lines of point m+2 (slices of ceil(K/D) or floor(K/D) lines; 400 lines ->
// exactly 50 per tick at 20 kHz, 25 at 40 kHz). The worst case is therefore fixed by K alone,
// whatever the phases.
//
// Cost (arm-none-eabi-g++ 12 -O2, counted under QEMU -icount): 16 instructions per line (a
// phase add, one table sample's value and slope, one convert, one FPU multiply-add, the sum)
// plus ~60 per tick; ProgramRunner::step() with 400 lines is ~900 instructions at 20 kHz (50
// lines) and ~500 at 40 kHz (25 lines), with 90 lines ~300. On the STM32G474 count ~1.3-1.5 cycles per instruction
// from zero-wait RAM, so about 1300-1500 of the 4250-cycle budget at 20 kHz. The table is const
// data (flash): for cache-independent timing a board can place the symbol
// palp::fw::detail::kSineTable (section .rodata._ZN4palp2fw6detail10kSineTableE with
// -fdata-sections) in CCM SRAM.
//
// Phases are exact: the fundamental's phase at each point, theta = frac(t / T) as a u32 fraction
// of a turn, advances by exact integer steps (quotient and remainder of D 2^32 / P, P = period
// ticks), and line n's phase is phi_n + h_n theta (mod 2^32): one multiply-add per line and no
// accumulated rounding. The phases repeat exactly every period; the output repeats bit for bit
// when P is a multiple of D (the default: P = 400000 ticks).
//
// Error (per unit line amplitude): linear interpolation of a line of frequency f between points
// Ts = 1 / 2500 s apart is off by at most (2 pi f Ts)^2 / 8 at any instant, and attenuates the
// line by about 1 - sinc^2(f Ts) ~ (pi f Ts)^2 / 3 (its in-band amplitude error; exactly
// multisine_amplitude_error()). For the default program's highest line (19.85 Hz): 3.1e-4 peak,
// 2.0e-4 in amplitude. The highest line a program may have is kMultisineMaxLine_Hz = 125 Hz
// (f Ts = 1/20): 1.2 % peak, 0.81 % in amplitude; a faster line is refused at load
// (ErrorCode::out_of_range). The table lookup adds kSineMaxError per line and the float sums
// about K^2 2^-24. multisine_error_bound() adds these up, line by line, for a given program; the
// tests hold the generator to it against a double-precision sum.
#pragma once

#include <array>
#include <cstdint>

#include "palp/protocol/messages.hpp"

namespace palp::fw {

inline constexpr std::uint32_t kMaxMultisineLines = 400;
inline constexpr std::uint32_t kMultisineSubRate_Hz = 2500;
/// Highest line frequency as a fraction of the sub-rate: 1/20 (125 Hz).
inline constexpr std::uint32_t kMultisineSubRatePerMaxLine = 20;
inline constexpr double kMultisineMaxLine_Hz =
    static_cast<double>(kMultisineSubRate_Hz) / kMultisineSubRatePerMaxLine;

/// The excited lines of a multisine, as the device runs them.
struct MultisineLines {
  std::uint32_t count = 0;         ///< K
  std::uint32_t first = 0;         ///< h_0
  std::uint32_t step = 0;          ///< h_{n+1} - h_n
  std::uint32_t period_ticks = 0;  ///< P
  std::uint32_t ticks_per_point = 0;  ///< D
  proto::PhaseMode phase_mode = proto::PhaseMode::zero;
  std::uint32_t phase_seed = 1;
  std::uint32_t highest() const { return first + (count - 1) * step; }
};

/// Worst-case |generated - exact| of the unit sum x for these lines (see the file comment).
double multisine_error_bound(const MultisineLines& lines, std::uint32_t rate_Hz);
/// In-band amplitude error of a line of frequency_Hz: the interpolation is a triangular filter
/// with gain (sin(pi f Ts) / (D sin(pi f Ts / D)))^2, about 1 - sinc^2(f Ts).
double multisine_amplitude_error(double frequency_Hz, std::uint32_t ticks_per_point);

class MultisineSynth {
 public:
  /// Load-time: stores the phases, primes points 0 and 1 (2 K line evaluations) and rewinds.
  /// lines.count must be 1 ... kMaxMultisineLines, ticks_per_point 1 ... kMaxTicksPerPoint and
  /// period_ticks >= 1 (values beyond are clamped, never written out of bounds).
  void configure(const MultisineLines& lines);
  /// Back to t = 0 in O(1) (the primed points are kept).
  void rewind();
  /// One tick: returns x at this tick and does this tick's slice of the next point.
  float step();
  /// Lines evaluated by the last step() (for the per-tick work accounting).
  std::uint32_t lines_last_step() const { return lines_last_step_; }
  /// Line n's phase phi_n as a u32 fraction of a turn (multisine_phase_turns()).
  std::uint32_t phase_turns(std::uint32_t n) const { return phase_[n] - (1u << 30); }
  /// The most lines any step() evaluates for this configuration: ceil(K / D).
  std::uint32_t max_lines_per_step() const;

  static constexpr std::uint32_t kMaxTicksPerPoint = 16;

 private:
  struct Theta {  // fundamental phase of a point: floor(frac(t / T) 2^32), exact
    std::uint32_t turns = 0;      // u32 fraction of a turn
    std::uint32_t remainder = 0;  // of the division by P, < P
  };
  void advance(Theta& th) const;
  float sum_lines(const Theta& th, std::uint32_t lo, std::uint32_t hi) const;
  float point_sum(const Theta& th) const;

  std::array<std::uint32_t, kMaxMultisineLines> phase_{};  // phi_n + a quarter turn (cos = sin)
  // slice s (the lines tick s of an interval sums): [slice_[s], slice_[s + 1])
  std::array<std::uint16_t, kMaxTicksPerPoint + 1> slice_{};
  std::uint32_t count_ = 0, first_ = 0, step_ = 0;
  std::uint32_t period_ = 1, per_point_ = 1;
  std::uint32_t theta_step_ = 0, theta_step_rem_ = 0;  // D 2^32 = theta_step_ P + theta_step_rem_
  // primed at configure(): x at points 0 and 1, theta of point 2
  float primed0_ = 0.0f, primed1_ = 0.0f;
  Theta primed_theta_{};
  // running state
  float x_prev_ = 0.0f, x_next_ = 0.0f, x_acc_ = 0.0f;  // points m, m+1, partial m+2
  Theta theta_{};                                       // of point m+2
  std::uint32_t sub_ = 0;                               // tick within the point interval
  float inv_per_point_ = 1.0f;
  std::uint32_t lines_last_step_ = 0;
};

}  // namespace palp::fw
