// SPDX-License-Identifier: Apache-2.0
// Program timing (program_schedule.hpp). Load-time code: double arithmetic is allowed here.
#include "palp/protocol/program_schedule.hpp"

namespace palp::proto {

std::uint32_t phase_increment(float frequency_Hz, std::uint32_t rate_Hz) {
  const double turns_per_tick = static_cast<double>(frequency_Hz) / static_cast<double>(rate_Hz);
  return static_cast<std::uint32_t>(turns_per_tick * 4294967296.0 + 0.5);
}

std::uint64_t phase_increment_fine(float frequency_Hz, std::uint32_t rate_Hz) {
  const double turns_per_tick = static_cast<double>(frequency_Hz) / static_cast<double>(rate_Hz);
  return static_cast<std::uint64_t>(turns_per_tick * 18446744073709551616.0 + 0.5);
}

std::uint32_t grid_points(float from, float to, float step) {
  const double span = static_cast<double>(to) - static_cast<double>(from);
  const double steps = (span < 0 ? -span : span) / static_cast<double>(step);
  return static_cast<std::uint32_t>(steps + kGridTolerance_steps) + 1;
}

std::uint64_t ticks_from_seconds(float seconds, std::uint32_t rate_Hz) {
  if (!(seconds > 0.0f)) return 0;
  const auto ticks =
      static_cast<std::uint64_t>(static_cast<double>(seconds) * rate_Hz + 0.5);
  return ticks == 0 ? 1 : ticks;
}

RampTiming ramp_timing(const LoadRamp& m, std::uint32_t rate_Hz) {
  RampTiming t;
  t.levels = grid_points(m.start_A, m.stop_A, m.step_A);
  t.stairs_per_rep = m.unload ? 2 * t.levels - 1 : t.levels;
  t.dwell_ticks = static_cast<std::uint32_t>(ticks_from_seconds(m.dwell_s, rate_Hz));
  t.ticks_per_rep = static_cast<std::uint64_t>(t.stairs_per_rep) * t.dwell_ticks;
  t.total_ticks = t.ticks_per_rep * m.repetitions;
  return t;
}

SweepPlan sweep_plan(const LoadSweep& m, std::uint32_t rate_Hz) {
  SweepPlan p;
  p.lines = grid_points(m.start_Hz, m.stop_Hz, m.step_Hz);
  p.start_fine = phase_increment_fine(m.start_Hz, rate_Hz);
  p.step_fine = phase_increment_fine(m.step_Hz, rate_Hz);
  p.settle_min_ticks = ticks_from_seconds(m.settle_min_s, rate_Hz);
  p.settle_cycles = m.settle_cycles;
  p.measure_cycles = m.measure_cycles;
  return p;
}

SweepLine sweep_line(const SweepPlan& p, std::uint32_t j) {
  SweepLine l;
  l.increment = coarse_increment(p.start_fine + p.step_fine * j);
  // ceil(x - 2^-13) for x = settle_min_ticks * increment / 2^32, in 32.32 fixed point
  const std::uint64_t x = p.settle_min_ticks * l.increment;
  const auto by_time = static_cast<std::uint32_t>((x + (1ull << 32) - 1 - (1ull << 19)) >> 32);
  l.settle_cycles = by_time > p.settle_cycles ? by_time : p.settle_cycles;
  l.cycles = l.settle_cycles + p.measure_cycles;
  return l;
}

std::uint64_t sweep_total_ticks(const SweepPlan& p) {
  std::uint64_t total = 0;
  for (std::uint32_t j = 0; j < p.lines; ++j) total += sweep_line_ticks(sweep_line(p, j));
  return total;
}

std::uint32_t multisine_period_ticks(float fundamental_Hz, std::uint32_t rate_Hz) {
  const double ticks = static_cast<double>(rate_Hz) / static_cast<double>(fundamental_Hz);
  return static_cast<std::uint32_t>(ticks + 0.5);
}

}  // namespace palp::proto
