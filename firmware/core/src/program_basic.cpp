// SPDX-License-Identifier: Apache-2.0
// Hold, contact watch and sine (program_kinds.hpp).
#include "palp/fw/program_kinds.hpp"
#include "palp/fw/waveform.hpp"

namespace palp::fw {

// ---- hold -----------------------------------------------------------------------------------
proto::ErrorCode HoldProgram::validate(const proto::LoadHold&, std::uint32_t, std::uint8_t&) {
  return proto::ErrorCode::ok;  // the catalogue ranges say it all
}

void HoldProgram::load(const proto::LoadHold& m, std::uint32_t rate_Hz) {
  current_A_ = m.current_A;
  duration_ticks_ = proto::ticks_from_seconds(m.duration_s, rate_Hz);
}

void HoldProgram::step(std::uint64_t k, std::int32_t, ProgramTick& out) const {
  if (duration_ticks_ != 0 && k >= duration_ticks_) {
    out.ended = true;
    out.end = proto::ProgramEnd::completed;
    return;
  }
  out.current_A = current_A_;
}

// ---- contact watch --------------------------------------------------------------------------
proto::ErrorCode ContactWatchProgram::validate(const proto::LoadContactWatch&, std::uint32_t,
                                               std::uint8_t&) {
  return proto::ErrorCode::ok;
}

void ContactWatchProgram::load(const proto::LoadContactWatch& m, std::uint32_t rate_Hz) {
  hold_current_A_ = m.hold_current_A;
  threshold_counts_ = m.threshold_counts;
  timeout_ticks_ = proto::ticks_from_seconds(m.timeout_s, rate_Hz);
}

void ContactWatchProgram::step(std::uint64_t k, std::int32_t encoder_count,
                               ProgramTick& out) const {
  if (timeout_ticks_ != 0 && k >= timeout_ticks_) {
    out.ended = true;
    out.end = proto::ProgramEnd::timeout;
    return;
  }
  out.current_A = hold_current_A_;
  const std::int64_t moved = static_cast<std::int64_t>(encoder_count) - armed_count_;
  if ((moved < 0 ? -moved : moved) >= threshold_counts_) {
    out.ended = true;
    out.end = proto::ProgramEnd::contact;
    out.contact = true;
  }
}

// ---- sine -----------------------------------------------------------------------------------
proto::ErrorCode SineProgram::validate(const proto::LoadSine& m, std::uint32_t,
                                       std::uint8_t& field_index) {
  if (!detail::peak_within_limit(m.offset_A, m.amplitude_A))
    return detail::out_of_range<&proto::LoadSine::amplitude_A>(field_index);
  return proto::ErrorCode::ok;
}

void SineProgram::load(const proto::LoadSine& m, std::uint32_t rate_Hz) {
  offset_A_ = m.offset_A;
  amplitude_A_ = m.amplitude_A;
  increment_ = proto::phase_increment(m.frequency_Hz, rate_Hz);
  cycles_total_ = m.cycles;
}

void SineProgram::start(std::int32_t) {
  previous_ahead_ = increment_ / 2;
  cycles_done_ = 0;
}

void SineProgram::step(std::uint64_t k, std::int32_t, ProgramTick& out) {
  const std::uint32_t phase = static_cast<std::uint32_t>(k) * increment_;  // exact mod 2^32
  // a cycle completes on the tick nearest its end: where the phase half a tick ahead wraps
  const std::uint32_t ahead = phase + increment_ / 2;
  if (ahead < previous_ahead_) {
    ++cycles_done_;
    if (cycles_total_ != 0 && cycles_done_ == cycles_total_) {
      out.ended = true;
      out.end = proto::ProgramEnd::completed;
      out.step = cycles_done_;
      return;
    }
  }
  previous_ahead_ = ahead;
  out.current_A = offset_A_ + amplitude_A_ * sin_turns(phase);
  out.step = cycles_done_;
}

std::uint16_t SineProgram::repetitions_done() const {
  return cycles_done_ > 0xFFFFu ? 0xFFFFu : static_cast<std::uint16_t>(cycles_done_);
}

}  // namespace palp::fw
