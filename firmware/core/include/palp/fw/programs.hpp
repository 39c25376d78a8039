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
// called with consecutive tick indices (a skipped tick is a control overrun, which the
// controller turns into a fault and abort_fault()).
//
// Set-point when no program runs ("rest" current): 0 A, except after a contact watch ended with
// ProgramEnd::contact, which keeps hold_current_A on (the probe stays in contact while the robot
// stops) until stop(), abort_fault() or the next start(). Every other end - completed,
// stopped_by_host, fault, timeout - puts the set-point to 0 A at once, in the same tick.
//
// Representation: one class per program in a tagged union (kind + union), dispatched with a
// switch; no virtual functions, no heap. sizeof(ProgramRunner) is about 1.8 KB, nearly all of
// it the multisine's 400 line phases.
//
// Context: not thread-safe. start/stop/abort_fault/step/adopt belong to the control tick's
// context (or to code that runs with the tick masked). load() is load-time work; measured on the
// QEMU Cortex-M4 (-O2): a 400-line multisine ~21000 instructions (random phases) or ~25000
// (Schroeder), mostly priming two sub-rate points (800 line evaluations): 3-4 ticks at 20 kHz;
// the default 90-line multisine ~7400; a ramp ~2100, a sweep ~2800 (soft double arithmetic), a
// sine ~1000, a hold or contact watch < 100. start() < 150. So the controller never loads the
// live runner: it loads a spare one with the tick running and adopt()s it in a short masked
// section (a copy of the program only, at most ~1.7 KB).
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
  /// unsupported control rate.
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

  /// Takes over the program `staged` holds (loaded there by load(), outside the tick): this
  /// runner ends up exactly as if it had loaded the same message itself. The runtime state stays:
  /// a contact hold's rest current, contact_latched, the last run's end and times. busy while a
  /// program runs here, no_program when `staged` has nothing loaded (this runner unchanged).
  /// Costs a copy of the staged program: at most ~1.7 KB (a 400-line multisine).
  proto::ErrorCode adopt(const ProgramRunner& staged);

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
    return kind_ == proto::ProgramKind::multisine ? &slot_.multisine : nullptr;
  }

 private:
  template <class Program, class Message>
  proto::ErrorCode load_as(Program& slot, proto::ProgramKind kind, const Message& m,
                           std::uint32_t rate_Hz, std::uint8_t& field_index);
  bool end_run(std::uint64_t now_ticks, proto::ProgramEnd end);

  union Slot {
    Slot() : hold() {}
    HoldProgram hold;
    RampProgram ramp;
    SineProgram sine;
    SweepProgram sweep;
    MultisineProgram multisine;
    ContactWatchProgram contact;
  } slot_;
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
};

}  // namespace palp::fw
