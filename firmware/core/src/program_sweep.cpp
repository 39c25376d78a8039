// SPDX-License-Identifier: Apache-2.0
// The stepped-sine sweep (program_kinds.hpp, program_schedule.hpp).
#include "palp/fw/program_kinds.hpp"
#include "palp/fw/waveform.hpp"

namespace palp::fw {

proto::ErrorCode SweepProgram::validate(const proto::LoadSweep& m, std::uint32_t,
                                        std::uint8_t& field_index) {
  if (!detail::peak_within_limit(m.offset_A, m.amplitude_A))
    return detail::out_of_range<&proto::LoadSweep::amplitude_A>(field_index);
  if (m.stop_Hz < m.start_Hz) return detail::out_of_range<&proto::LoadSweep::stop_Hz>(field_index);
  // a step that cannot reach stop_Hz
  if (m.stop_Hz != m.start_Hz && proto::grid_points(m.start_Hz, m.stop_Hz, m.step_Hz) < 2)
    return detail::out_of_range<&proto::LoadSweep::step_Hz>(field_index);
  return proto::ErrorCode::ok;
}

void SweepProgram::load(const proto::LoadSweep& m, std::uint32_t rate_Hz) {
  plan_ = proto::sweep_plan(m, rate_Hz);
  offset_A_ = m.offset_A;
  amplitude_A_ = m.amplitude_A;
}

void SweepProgram::start(std::int32_t) {
  line_ = 0;
  begin_line();
}

void SweepProgram::begin_line() {
  current_ = proto::sweep_line(plan_, line_);
  tick_ = 0;
  previous_ahead_ = current_.increment / 2;
  cycles_done_ = 0;
}

void SweepProgram::step(std::uint64_t, std::int32_t, ProgramTick& out) {
  std::uint32_t phase = tick_ * current_.increment;
  // cycles complete on the tick nearest their end: where the phase half a tick ahead wraps
  const std::uint32_t ahead = phase + current_.increment / 2;
  if (ahead < previous_ahead_ && ++cycles_done_ == current_.cycles) {  // the line is complete
    if (++line_ == plan_.lines) {
      out.ended = true;
      out.end = proto::ProgramEnd::completed;
      out.step = line_ - 1;
      return;
    }
    begin_line();
    phase = 0;
  } else {
    previous_ahead_ = ahead;
  }
  ++tick_;
  out.current_A = offset_A_ + amplitude_A_ * sin_turns(phase);
  out.step = line_;
  out.measuring = cycles_done_ >= current_.settle_cycles;
}

std::uint16_t SweepProgram::repetitions_done() const {
  return line_ > 0xFFFFu ? 0xFFFFu : static_cast<std::uint16_t>(line_);
}

}  // namespace palp::fw
