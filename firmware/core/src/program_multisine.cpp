// SPDX-License-Identifier: Apache-2.0
// The periodic multisine program (program_kinds.hpp, multisine_synth.hpp).
#include "palp/fw/program_kinds.hpp"
#include "palp/protocol/multisine.hpp"

namespace palp::fw {

MultisineLines MultisineProgram::lines_of(const proto::LoadMultisine& m, std::uint32_t rate_Hz) {
  MultisineLines l;
  l.count = proto::multisine_line_count(m.line_first, m.line_last, m.line_step);
  l.first = m.line_first;
  l.step = m.line_step;
  l.period_ticks = proto::multisine_period_ticks(m.fundamental_Hz, rate_Hz);
  l.ticks_per_point = rate_Hz / kMultisineSubRate_Hz;
  l.phase_mode = m.phase_mode;
  l.phase_seed = m.phase_seed;
  return l;
}

proto::ErrorCode MultisineProgram::validate(const proto::LoadMultisine& m, std::uint32_t rate_Hz,
                                            std::uint8_t& field_index) {
  const MultisineLines l = lines_of(m, rate_Hz);
  // line_last: no line, more than kMaxMultisineLines, or a highest line above
  // kMultisineMaxLine_Hz (h_max rate / P > rate / (D 20), in integers)
  if (l.count == 0 || l.count > kMaxMultisineLines ||
      static_cast<std::uint64_t>(l.highest()) * l.ticks_per_point * kMultisineSubRatePerMaxLine >
          l.period_ticks)
    return detail::out_of_range<&proto::LoadMultisine::line_last>(field_index);
  // worst case: the K lines peak together at K * line_amplitude_A
  if (!detail::peak_within_limit(m.offset_A, static_cast<double>(m.line_amplitude_A) * l.count))
    return detail::out_of_range<&proto::LoadMultisine::line_amplitude_A>(field_index);
  switch (m.phase_mode) {
    case proto::PhaseMode::random_seeded:
    case proto::PhaseMode::schroeder:
    case proto::PhaseMode::zero:
      break;
    default:
      return detail::out_of_range<&proto::LoadMultisine::phase_mode>(field_index);  // unknown
  }
  return proto::ErrorCode::ok;
}

void MultisineProgram::load(const proto::LoadMultisine& m, std::uint32_t rate_Hz) {
  const MultisineLines l = lines_of(m, rate_Hz);
  synth_.configure(l);
  offset_A_ = m.offset_A;
  amplitude_A_ = m.line_amplitude_A;
  period_ticks_ = l.period_ticks;
  periods_ = m.periods;
}

void MultisineProgram::start(std::int32_t) {
  synth_.rewind();
  tick_in_period_ = 0;
  periods_done_ = 0;
}

void MultisineProgram::step(std::uint64_t, std::int32_t, ProgramTick& out) {
  if (tick_in_period_ == period_ticks_) {
    tick_in_period_ = 0;
    ++periods_done_;
    if (periods_ != 0 && periods_done_ == periods_) {
      out.ended = true;
      out.end = proto::ProgramEnd::completed;
      out.repetition = static_cast<std::uint16_t>(periods_done_ - 1);
      return;
    }
  }
  ++tick_in_period_;
  out.current_A = offset_A_ + amplitude_A_ * synth_.step();
  out.repetition = repetitions_done();
}

std::uint16_t MultisineProgram::repetitions_done() const {
  return periods_done_ > 0xFFFFu ? 0xFFFFu : static_cast<std::uint16_t>(periods_done_);
}

}  // namespace palp::fw
