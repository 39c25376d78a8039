// SPDX-License-Identifier: Apache-2.0
// The staircase ramp (program_kinds.hpp, program_schedule.hpp).
#include "palp/fw/program_kinds.hpp"

namespace palp::fw {

proto::ErrorCode RampProgram::validate(const proto::LoadRamp& m, std::uint32_t,
                                       std::uint8_t& field_index) {
  // a step longer than the way from start_A to stop_A never reaches stop_A (start_A == stop_A is
  // a one-level ramp)
  if (m.start_A != m.stop_A && proto::grid_points(m.start_A, m.stop_A, m.step_A) < 2)
    return detail::out_of_range<&proto::LoadRamp::step_A>(field_index);
  return proto::ErrorCode::ok;
}

void RampProgram::load(const proto::LoadRamp& m, std::uint32_t rate_Hz) {
  timing_ = proto::ramp_timing(m, rate_Hz);
  start_A_ = m.start_A;
  step_A_ = m.stop_A < m.start_A ? -m.step_A : m.step_A;
  reps_ = m.repetitions;
  unload_ = m.unload != 0;
  limit_counts_ = m.displacement_limit_counts;
}

void RampProgram::start(std::int32_t encoder_count) {
  start_count_ = encoder_count;
  rep_ = 0;
  stair_ = 0;
  climbing_ = true;
  turned_ = false;
  stair_end_ = timing_.dwell_ticks;
  set_level(0);
}

void RampProgram::set_level(std::uint32_t level) {
  level_ = level;
  current_A_ = start_A_ + step_A_ * static_cast<float>(level);  // no accumulated sums
}

bool RampProgram::next_rep() {
  if (++rep_ == reps_) return false;
  stair_ = 0;
  climbing_ = true;
  turned_ = false;
  set_level(0);
  return true;
}

bool RampProgram::advance() {
  if (climbing_ && !turned_ && level_ + 1 < timing_.levels) {
    set_level(level_ + 1);
  } else if (climbing_ && unload_ && level_ > 0) {  // the top: turn round
    climbing_ = false;
    set_level(level_ - 1);
  } else if (!climbing_ && level_ > 0) {
    set_level(level_ - 1);
  } else {
    return next_rep();
  }
  ++stair_;
  return true;
}

void RampProgram::step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out) {
  bool running = true;
  if (climbing_ && limit_counts_ != 0 && !turned_) {
    const std::int64_t moved = static_cast<std::int64_t>(encoder_count) - start_count_;
    if ((moved < 0 ? -moved : moved) >= limit_counts_) {
      turned_ = true;  // this level is the top of the repetition
      if (level_ > 0) {  // cut its dwell short; level 0 keeps its dwell
        running = advance();
        stair_end_ = k + timing_.dwell_ticks;
      }
    }
  }
  if (running && k >= stair_end_) {
    stair_end_ += timing_.dwell_ticks;
    running = advance();
  }
  out.step = stair_;
  out.repetition = rep_;
  if (!running) {
    out.ended = true;
    out.end = proto::ProgramEnd::completed;
    return;
  }
  out.current_A = current_A_;
}

}  // namespace palp::fw
