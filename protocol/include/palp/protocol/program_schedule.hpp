// SPDX-License-Identifier: Apache-2.0
// Program timing as pure functions of a Load* message and the control rate: how many levels,
// lines and ticks a program has, exactly as the device runs it. The host needs the same numbers
// to cut a recording into ramp levels and sweep lines, so everything here is integer arithmetic
// on values derived once, at load, with double arithmetic that is reproducible bit for bit on any
// IEEE-754 machine (no libm, no fused operations). One definition for the firmware, which runs the
// programs, and the host, which cuts their recordings.
//
// Time is counted in control ticks from ProgramStart: tick k is the k-th call of the program's
// step, at device time start + k / control_rate_Hz.
#pragma once

#include <cstdint>

#include "palp/protocol/messages.hpp"

namespace palp::proto {

/// The control rates a device runs at (Params.control_rate_Hz).
constexpr bool is_supported_control_rate(std::uint32_t rate_Hz) {
  return rate_Hz == 20000 || rate_Hz == 40000;
}

/// Largest current magnitude a program may ever ask for: the catalogue's current range. The
/// controller clamps further to Params.current_clamp_A.
inline constexpr double kProgramMaxCurrent_A = 4.0;

/// A stop value counts as on the grid when within this fraction of a step of it (absorbs the
/// f32 rounding of values such as 0.01 or 0.05).
inline constexpr double kGridTolerance_steps = 1e-3;

// ---- phase increments ------------------------------------------------------------------------
// A u32 phase p is the angle p / 2^32 turns. A tone of f_Hz at control rate R advances by
// phase_increment(f, R) per tick; its realised frequency is increment * R / 2^32.

/// round(frequency_Hz / rate_Hz * 2^32): the per-tick phase increment of a tone. For
/// 0 <= frequency_Hz < rate_Hz / 2 (the programs allow at most 2000 Hz at 20 kHz). Load-time
/// code (double arithmetic; reproducible bit for bit on any IEEE-754 machine).
std::uint32_t phase_increment(float frequency_Hz, std::uint32_t rate_Hz);

/// The same increment with 32 more fraction bits, round(frequency_Hz / rate_Hz * 2^64) (to the
/// 53 bits of a double): for frequency grids whose lines must not accumulate rounding.
std::uint64_t phase_increment_fine(float frequency_Hz, std::uint32_t rate_Hz);

/// The u32 increment nearest a fine one: (fine + 2^31) >> 32.
constexpr std::uint32_t coarse_increment(std::uint64_t fine) {
  return static_cast<std::uint32_t>((fine + (1ull << 31)) >> 32);
}

// ---- grids and durations ---------------------------------------------------------------------

/// Number of grid points from `from` toward `to` by `step` (> 0), `to` included when on the grid:
/// floor(|to - from| / step + kGridTolerance_steps) + 1.
std::uint32_t grid_points(float from, float to, float step);

/// round(seconds * rate_Hz) ticks; a positive duration is at least one tick.
std::uint64_t ticks_from_seconds(float seconds, std::uint32_t rate_Hz);

/// Ticks a tone with phase increment `increment` (> 0) takes for `cycles` whole cycles, to the
/// nearest tick: the first tick k with k * increment + increment / 2 >= cycles * 2^32 (integer
/// halving), i.e. ceil((cycles * 2^32 - increment / 2) / increment). A program running `cycles`
/// cycles outputs ticks 0 ... this - 1; its phase at this tick is within half an increment of
/// a whole turn. The device finds the same tick by counting wraps of the phase plus half an
/// increment.
constexpr std::uint64_t ticks_for_cycles(std::uint64_t cycles, std::uint32_t increment) {
  return ((cycles << 32) - increment / 2 + increment - 1) / increment;
}

// ---- staircase ramp ---------------------------------------------------------------------------
// Levels j = 0 ... levels - 1 at start_A + j * step_A toward stop_A (stop_A itself when on the
// grid: 0.5 -> 3 A by 0.01 A gives 251 levels). A repetition climbs 0, 1, ..., levels - 1 and, if
// unload, comes back down levels - 2, ..., 0: the top level is held once, the start level at both
// ends (so twice in a row between two repetitions); every stair lasts dwell ticks. Without unload
// a repetition is the climb alone and the next one starts again at level 0.
struct RampTiming {
  std::uint32_t levels = 0;          ///< levels of the climb
  std::uint32_t stairs_per_rep = 0;  ///< 2 * levels - 1 with unload, levels without
  std::uint32_t dwell_ticks = 0;     ///< round(dwell_s * rate), >= 1
  std::uint64_t ticks_per_rep = 0;   ///< stairs_per_rep * dwell_ticks
  std::uint64_t total_ticks = 0;     ///< repetitions * ticks_per_rep (no displacement limit)
};
RampTiming ramp_timing(const LoadRamp& m, std::uint32_t rate_Hz);

/// The level of tick k (< total_ticks) when no displacement limit turns the ramp early.
constexpr std::uint32_t ramp_level_at(const RampTiming& t, std::uint64_t k) {
  const auto stair = static_cast<std::uint32_t>((k % t.ticks_per_rep) / t.dwell_ticks);
  return stair < t.levels ? stair : 2 * (t.levels - 1) - stair;
}

// ---- stepped-sine sweep -------------------------------------------------------------------------
// Lines j = 0 ... lines - 1 at start_Hz + j * step_Hz (stop_Hz included when on the grid: 2 -> 20
// Hz by 0.05 Hz gives 361 lines). Line j's phase increment is the nearest u32 to
// start_fine + j * step_fine (the fine, 64-bit increments of start_Hz and step_Hz), so the grid
// does not accumulate rounding. Every line starts at phase 0 and runs whole cycles: it settles
// for S_j = max(settle_cycles, ceil(settle_min_ticks * increment_j / 2^32 - 2^-13)) cycles (the
// cycles that cover settle_min_s, a line whose count is within 2^-13 cycle of a whole number
// takes that number), then measures measure_cycles cycles. Boundaries fall on the nearest tick
// (ticks_for_cycles): line j lasts ticks_for_cycles(S_j + measure_cycles, increment_j) ticks,
// its measurement starts at tick ticks_for_cycles(S_j, increment_j), and the tick after its last
// is tick 0 (phase 0) of the next line.
struct SweepPlan {
  std::uint32_t lines = 0;
  std::uint64_t start_fine = 0;        ///< phase_increment_fine(start_Hz)
  std::uint64_t step_fine = 0;         ///< phase_increment_fine(step_Hz)
  std::uint64_t settle_min_ticks = 0;  ///< round(settle_min_s * rate)
  std::uint32_t settle_cycles = 0;
  std::uint32_t measure_cycles = 0;
};
SweepPlan sweep_plan(const LoadSweep& m, std::uint32_t rate_Hz);

struct SweepLine {
  std::uint32_t increment = 0;      ///< phase increment per tick
  std::uint32_t settle_cycles = 0;  ///< S_j
  std::uint32_t cycles = 0;         ///< S_j + measure_cycles
};
/// Line j's increment and cycle counts (cheap: multiplications and shifts only).
SweepLine sweep_line(const SweepPlan& p, std::uint32_t j);

/// Line j's settle and total ticks (one 64-bit division each: for the host and tests, not the
/// tick; the device finds the same boundaries by counting phase wraps).
inline std::uint64_t sweep_settle_ticks(const SweepLine& l) {
  return ticks_for_cycles(l.settle_cycles, l.increment);
}
inline std::uint64_t sweep_line_ticks(const SweepLine& l) {
  return ticks_for_cycles(l.cycles, l.increment);
}
/// The whole sweep, in ticks (loops over every line).
std::uint64_t sweep_total_ticks(const SweepPlan& p);

// ---- multisine ------------------------------------------------------------------------------
// One period is a whole number of ticks, P = round(rate / fundamental_Hz), so every period is
// identical and a record of whole periods has no leakage: the realised fundamental is rate / P
// (exact for the default 0.05 Hz; within 1 / (2P) of fundamental_Hz, 2.5e-5 at 1 Hz).
std::uint32_t multisine_period_ticks(float fundamental_Hz, std::uint32_t rate_Hz);

}  // namespace palp::proto
