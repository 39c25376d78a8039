// SPDX-License-Identifier: Apache-2.0
// ProgramRunner (programs.hpp): validation, the program life cycle and the per-tick dispatch.
#include "palp/fw/programs.hpp"

#include <new>
#include <type_traits>

namespace palp::fw {

static_assert(std::is_trivially_destructible_v<HoldProgram> &&
                  std::is_trivially_destructible_v<RampProgram> &&
                  std::is_trivially_destructible_v<SineProgram> &&
                  std::is_trivially_destructible_v<SweepProgram> &&
                  std::is_trivially_destructible_v<MultisineProgram> &&
                  std::is_trivially_destructible_v<ContactWatchProgram>,
              "the union switches members by constructing over them");
static_assert(std::is_trivially_copyable_v<ProgramRunner>,
              "a runner is a plain value: tests and tools copy loaded runners");

template <class Program, class Message>
proto::ErrorCode ProgramRunner::stage_as(Program Slot::*member, proto::ProgramKind kind,
                                         const Message& m, std::uint32_t rate_Hz,
                                         std::uint8_t& field_index) {
  field_index = 255;
  if (!proto::is_supported_control_rate(rate_Hz)) return proto::ErrorCode::out_of_range;
  const int bad = m.first_out_of_range();
  if (bad >= 0) return detail::out_of_range(static_cast<std::uint8_t>(bad), field_index);
  const proto::ErrorCode e = Program::validate(m, rate_Hz, field_index);
  if (e != proto::ErrorCode::ok) return e;
  Program& staging = slots_[active_ ^ 1u].*member;
  ::new (static_cast<void*>(&staging)) Program();
  staging.load(m, rate_Hz);
  staged_kind_ = kind;
  staged_rate_Hz_ = rate_Hz;
  return proto::ErrorCode::ok;
}

proto::ErrorCode ProgramRunner::adopt_staged() {
  if (running()) return proto::ErrorCode::busy;
  if (staged_kind_ == proto::ProgramKind::none) return proto::ErrorCode::no_program;
  // what a load sets; everything else is the runtime state and stays
  active_ ^= 1u;
  kind_ = staged_kind_;
  state_ = proto::ProgramState::loaded;
  rate_Hz_ = staged_rate_Hz_;
  step_ = 0;
  repetition_ = 0;
  staged_kind_ = proto::ProgramKind::none;
  return proto::ErrorCode::ok;
}

proto::ErrorCode ProgramRunner::stage(const proto::LoadHold& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::hold, proto::ProgramKind::hold, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::stage(const proto::LoadRamp& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::ramp, proto::ProgramKind::ramp, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::stage(const proto::LoadSine& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::sine, proto::ProgramKind::sine, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::stage(const proto::LoadSweep& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::sweep, proto::ProgramKind::sweep, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::stage(const proto::LoadMultisine& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::multisine, proto::ProgramKind::multisine, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::stage(const proto::LoadContactWatch& m, std::uint32_t rate_Hz,
                                      std::uint8_t& field_index) {
  return stage_as(&Slot::contact, proto::ProgramKind::contact_watch, m, rate_Hz, field_index);
}

namespace {
// load() for every Load* message: the busy check, then stage() and adopt_staged()
template <class Message>
proto::ErrorCode load_via_stage(ProgramRunner& r, const Message& m, std::uint32_t rate_Hz,
                                std::uint8_t& field_index) {
  field_index = 255;
  if (r.running()) return proto::ErrorCode::busy;
  const proto::ErrorCode e = r.stage(m, rate_Hz, field_index);
  return e != proto::ErrorCode::ok ? e : r.adopt_staged();
}
}  // namespace

proto::ErrorCode ProgramRunner::load(const proto::LoadHold& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::load(const proto::LoadRamp& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::load(const proto::LoadSine& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::load(const proto::LoadSweep& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::load(const proto::LoadMultisine& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}
proto::ErrorCode ProgramRunner::load(const proto::LoadContactWatch& m, std::uint32_t rate_Hz,
                                     std::uint8_t& field_index) {
  return load_via_stage(*this, m, rate_Hz, field_index);
}

proto::ErrorCode ProgramRunner::start(std::uint64_t now_ticks, std::int32_t encoder_count) {
  if (state_ == proto::ProgramState::idle) return proto::ErrorCode::no_program;
  if (running()) return proto::ErrorCode::busy;
  switch (kind_) {
    case proto::ProgramKind::hold: slot().hold.start(encoder_count); break;
    case proto::ProgramKind::ramp: slot().ramp.start(encoder_count); break;
    case proto::ProgramKind::sine: slot().sine.start(encoder_count); break;
    case proto::ProgramKind::sweep: slot().sweep.start(encoder_count); break;
    case proto::ProgramKind::multisine: slot().multisine.start(encoder_count); break;
    case proto::ProgramKind::contact_watch: slot().contact.start(encoder_count); break;
    default: return proto::ErrorCode::no_program;
  }
  state_ = proto::ProgramState::running;
  end_ = proto::ProgramEnd::completed;
  start_tick_ = end_tick_ = now_ticks;
  armed_count_ = encoder_count;
  contact_latched_ = false;
  rest_current_A_ = 0.0f;
  step_ = 0;
  repetition_ = 0;
  return proto::ErrorCode::ok;
}

ProgramStep ProgramRunner::step(std::uint64_t now_ticks, std::int32_t encoder_count) {
  ProgramStep out;
  if (!running()) {
    out.current_A = rest_current_A_;
    out.step = step_;
    out.repetition = repetition_;
    return out;
  }
  const std::uint64_t k = now_ticks - start_tick_;
  ProgramTick t;
  switch (kind_) {
    case proto::ProgramKind::hold: slot().hold.step(k, encoder_count, t); break;
    case proto::ProgramKind::ramp: slot().ramp.step(k, encoder_count, t); break;
    case proto::ProgramKind::sine: slot().sine.step(k, encoder_count, t); break;
    case proto::ProgramKind::sweep: slot().sweep.step(k, encoder_count, t); break;
    case proto::ProgramKind::multisine: slot().multisine.step(k, encoder_count, t); break;
    case proto::ProgramKind::contact_watch: slot().contact.step(k, encoder_count, t); break;
    default: t.ended = true; t.end = proto::ProgramEnd::fault; break;  // unreachable
  }
  if (!t.ended) {
    step_ = t.step;
    repetition_ = t.repetition;
    out.current_A = t.current_A;
    out.running = true;
  } else {
    state_ = proto::ProgramState::finished;
    end_ = t.end;
    end_tick_ = now_ticks;
    rest_current_A_ = t.end == proto::ProgramEnd::contact ? t.current_A : 0.0f;
    contact_latched_ = t.contact;
    out.current_A = rest_current_A_;
    out.finished = true;
    out.end = t.end;
    out.contact = t.contact;
    out.contact_count = encoder_count;
  }
  out.measuring = t.measuring;
  out.step = step_;
  out.repetition = repetition_;
  return out;
}

bool ProgramRunner::end_run(std::uint64_t now_ticks, proto::ProgramEnd end) {
  rest_current_A_ = 0.0f;
  if (!running()) return false;
  state_ = proto::ProgramState::finished;
  end_ = end;
  end_tick_ = now_ticks;
  return true;
}

bool ProgramRunner::stop(std::uint64_t now_ticks) {
  return end_run(now_ticks, proto::ProgramEnd::stopped_by_host);
}

bool ProgramRunner::abort_fault(std::uint64_t now_ticks) {
  return end_run(now_ticks, proto::ProgramEnd::fault);
}

std::uint16_t ProgramRunner::repetitions_done() const {
  switch (kind_) {
    case proto::ProgramKind::ramp: return slot().ramp.repetitions_done();
    case proto::ProgramKind::sine: return slot().sine.repetitions_done();
    case proto::ProgramKind::sweep: return slot().sweep.repetitions_done();
    case proto::ProgramKind::multisine: return slot().multisine.repetitions_done();
    default: return 0;
  }
}

std::uint64_t ProgramRunner::elapsed_ticks(std::uint64_t now_ticks) const {
  switch (state_) {
    case proto::ProgramState::running: return now_ticks - start_tick_;
    case proto::ProgramState::finished: return end_tick_ - start_tick_;
    default: return 0;
  }
}

proto::ProgramStatus ProgramRunner::status(std::uint64_t now_ticks) const {
  proto::ProgramStatus s;
  s.kind = kind_;
  s.state = state_;
  s.end = end_;
  s.elapsed_us = elapsed_ticks(now_ticks) * (1000000u / rate_Hz_);  // 50 or 25 us per tick
  s.step = step_;
  s.repetition = repetition_;
  return s;
}

}  // namespace palp::fw
