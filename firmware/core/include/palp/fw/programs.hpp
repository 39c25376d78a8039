// SPDX-License-Identifier: Apache-2.0
// ProgramRunner: the on-device waveform programs (DESIGN.md "Firmware principles"). The host
// sends a program's parameters (LoadHold ... LoadContactWatch) and ProgramStart; from then on the
// control tick calls step() once per tick and gets the coil current set-point, with no host or
// USB timing involved.
//
// The programs (details in program_kinds.hpp, timing in program_schedule.hpp):
//   hold           current_A for duration_s (0: until stopped)
//   ramp           staircase start_A -> stop_A by step_A, dwell_s per level, symmetric unload,
//                  repetitions, optional displacement limit that turns the climb early
//   sine           offset_A + amplitude_A sin(2 pi f t) for `cycles` whole cycles from phase 0
//   sweep          stepped sine, each line settled then measured in whole cycles from phase 0
//   multisine      `periods` whole periods of the SPEC's multisine (up to 400 lines)
//   contact watch  hold_current_A until the encoder moves threshold_counts (ProgramEnd::contact)
//                  or timeout_s passes (ProgramEnd::timeout)
//
// Life: idle --load--> loaded --start--> running --(end)--> finished --start--> running ...
// A finished program stays loaded and can be started again. Time is the control tick index:
// start(now) then step(now) in the same tick gives the program's tick 0; step() must then be
// called with consecutive tick indices. The controller's tick index counts only ticks that ran:
// a tick the board could not run (TickInputs::missed_ticks) is counted in
// Health.control_overruns and shifts the program's device time, not its steps.
//
// Set-point when no program runs ("rest" current): 0 A, except after a contact watch ended with
// ProgramEnd::contact, which keeps hold_current_A on (the probe stays in contact while the robot
// stops) until stop(), abort_fault() or the next start(). Every other end - completed,
// stopped_by_host, fault, timeout - puts the set-point to 0 A at once, in the same tick.
//
// Representation: one class per program in a tagged union (kind + union), dispatched with a
// switch; no virtual functions, no heap. Two such slots: the active one, which the tick runs,
// and a staging one, which stage() fills; adopt_staged() swaps their roles. sizeof(ProgramRunner)
// is about 3.5 KB, nearly all of it the two slots' room for a multisine's 400 line phases.
//
// Contexts. Loading is load-time work, measured on the QEMU Cortex-M4 (-O2): a 400-line
// multisine ~21000 instructions (random phases) or ~25000 (Schroeder), mostly priming two
// sub-rate points (800 line evaluations): 3-4 ticks at 20 kHz; the default 90-line multisine
// ~7400; a ramp ~2100, a sweep ~2800 (soft double arithmetic), a sine ~1000, a hold or contact
// watch < 100. So the work is split: stage() writes only the staging slot and the staged kind
// and rate, which step() never reads, so it may run in the main loop while the tick runs;
// adopt_staged() (O(1): an index flip and a few fields) and start/stop/abort_fault/step belong to
// the tick's context or to code that runs with the tick masked. load() = stage() +
// adopt_staged(), for a caller that owns both contexts (tests, tools). start() < 150.
#pragma once

#include <cstdint>

#include "palp/fw/program_kinds.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::fw {

/// What the program did in this tick, for the controller.
struct ProgramStep {
  float current_A = 0.0f;  ///< coil current set-point for this tick (A)
  bool running = false;    ///< a program is running after this tick (StatusBit.program_running)
  /// The program ended at this tick: send EventProgramFinished{end, repetitions_done()}.
  bool finished = false;
  proto::ProgramEnd end = proto::ProgramEnd::completed;
  /// The contact watch fired at this tick: send EventContact{encoder_count = contact_count,
  /// armed_count = armed_count()}. `finished` is set too (end = contact).
  bool contact = false;
  std::int32_t contact_count = 0;
  bool measuring = false;        ///< sweep: inside a line's measured cycles
  std::uint32_t step = 0;        ///< ProgramStatus.step: stair, cycle or line index
  std::uint16_t repetition = 0;  ///< ProgramStatus.repetition: repetition or period index
};

class ProgramRunner {
 public:
  ProgramRunner() {}

  /// Validate and load a program for the control rate (20000 or 40000 Hz). Refusals (the
  /// previous program stays loaded): busy while running; out_of_range with the offending field
  /// (catalogue range first, then the program's own checks), or with field_index 255 for an
  /// unsupported control rate. stage() then adopt_staged().
  proto::ErrorCode load(const proto::LoadHold& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);
  proto::ErrorCode load(const proto::LoadRamp& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);
  proto::ErrorCode load(const proto::LoadSine& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);
  proto::ErrorCode load(const proto::LoadSweep& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);
  proto::ErrorCode load(const proto::LoadMultisine& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);
  proto::ErrorCode load(const proto::LoadContactWatch& m, std::uint32_t control_rate_Hz,
                        std::uint8_t& field_index);

  /// Validate a program and synthesise it into the staging slot, touching nothing the tick
  /// reads (see Contexts above). The same refusals as load() except busy: staging while a program
  /// runs leaves it running; the staged program waits for adopt_staged().
  proto::ErrorCode stage(const proto::LoadHold& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);
  proto::ErrorCode stage(const proto::LoadRamp& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);
  proto::ErrorCode stage(const proto::LoadSine& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);
  proto::ErrorCode stage(const proto::LoadSweep& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);
  proto::ErrorCode stage(const proto::LoadMultisine& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);
  proto::ErrorCode stage(const proto::LoadContactWatch& m, std::uint32_t control_rate_Hz,
                         std::uint8_t& field_index);

  /// The staged program becomes the loaded one, exactly as if load() had loaded it; the runtime
  /// state stays: a contact hold's rest current, contact_latched, the last run's end and times.
  /// busy while a program runs, no_program when nothing is staged (both: nothing changes). O(1).
  proto::ErrorCode adopt_staged();
  /// What stage() last staged and adopt_staged() has not yet taken (none if nothing).
  proto::ProgramKind staged_kind() const { return staged_kind_; }

  /// ProgramStart at tick now_ticks with the encoder count of that tick (the ramp's
  /// displacement reference and the contact watch's armed_count). no_program when nothing is
  /// loaded, busy while running. O(1).
  proto::ErrorCode start(std::uint64_t now_ticks, std::int32_t encoder_count);

  /// One control tick. Cheap for every program; the worst case is a 400-line multisine
  /// (50 line evaluations per tick at 20 kHz, 25 at 40 kHz; see multisine_synth.hpp).
  ProgramStep step(std::uint64_t now_ticks, std::int32_t encoder_count);

  /// ProgramStop: a running program ends with ProgramEnd::stopped_by_host and the set-point is
  /// 0 A at once (from the next step(), which also reports running = false). When nothing runs,
  /// drops a contact hold to 0 A. Returns whether a running program was ended (then send
  /// EventProgramFinished).
  bool stop(std::uint64_t now_ticks);
  /// A fault latched: as stop(), with ProgramEnd::fault.
  bool abort_fault(std::uint64_t now_ticks);

  proto::ProgramKind kind() const { return kind_; }
  proto::ProgramState state() const { return state_; }
  bool running() const { return state_ == proto::ProgramState::running; }
  /// How the last run ended (meaningful when finished).
  proto::ProgramEnd end() const { return end_; }
  /// Whole repetitions / cycles / lines / periods completed (EventProgramFinished).
  std::uint16_t repetitions_done() const;
  /// Encoder count at ProgramStart (EventContact.armed_count).
  std::int32_t armed_count() const { return armed_count_; }
  /// The contact watch fired and no program has been started since (StatusBit.contact_latched).
  bool contact_latched() const { return contact_latched_; }
  /// Set-point while no program runs (see the file comment).
  float rest_current_A() const { return rest_current_A_; }
  /// Ticks since ProgramStart (frozen at the end tick once finished).
  std::uint64_t elapsed_ticks(std::uint64_t now_ticks) const;
  /// The reply to GetProgramStatus.
  proto::ProgramStatus status(std::uint64_t now_ticks) const;

  /// The loaded multisine (kind() == multisine), for tests and per-tick work accounting.
  const MultisineProgram* multisine() const {
    return kind_ == proto::ProgramKind::multisine ? &slot().multisine : nullptr;
  }

 private:
  union Slot;
  template <class Program, class Message>
  proto::ErrorCode stage_as(Program Slot::*member, proto::ProgramKind kind, const Message& m,
                            std::uint32_t rate_Hz, std::uint8_t& field_index);
  bool end_run(std::uint64_t now_ticks, proto::ProgramEnd end);
  Slot& slot() { return slots_[active_]; }
  const Slot& slot() const { return slots_[active_]; }

  union Slot {
    Slot() : hold() {}
    HoldProgram hold;
    RampProgram ramp;
    SineProgram sine;
    SweepProgram sweep;
    MultisineProgram multisine;
    ContactWatchProgram contact;
  };
  Slot slots_[2];
  std::uint8_t active_ = 0;  // the slot the tick runs; the other is the staging slot
  proto::ProgramKind staged_kind_ = proto::ProgramKind::none;
  std::uint32_t staged_rate_Hz_ = 20000;
  proto::ProgramKind kind_ = proto::ProgramKind::none;
  proto::ProgramState state_ = proto::ProgramState::idle;
  proto::ProgramEnd end_ = proto::ProgramEnd::completed;
  std::uint32_t rate_Hz_ = 20000;
  std::uint64_t start_tick_ = 0, end_tick_ = 0;
  std::int32_t armed_count_ = 0;
  bool contact_latched_ = false;
  float rest_current_A_ = 0.0f;
  std::uint32_t step_ = 0;
  std::uint16_t repetition_ = 0;

  /// Tests only (tests/fw_core/test_tick_guard.cpp): tells the tick's part from the staging part.
  friend struct TickStateProbe;
};

}  // namespace palp::fw
