// SPDX-License-Identifier: Apache-2.0
// The six on-device programs, one small class each. ProgramRunner (programs.hpp) holds one of
// them at a time in a tagged union and is what the controller uses; this header is the detail.
//
// Every program has the same shape (no virtual functions: the runner switches on its kind):
//   static ErrorCode validate(const LoadX&, rate_Hz, field_index&)  semantics beyond the
//       catalogue ranges (which the runner checks first); on refusal names the field (Nak);
//   void load(const LoadX&, rate_Hz)        after validate() said ok; load-time work only;
//   void start(encoder_count)               back to tick 0; O(1);
//   void step(k, encoder_count, ProgramTick&)   tick k (0, 1, 2, ... consecutive) of the run;
//   uint16_t repetitions_done()             EventProgramFinished.repetitions_done.
// A program never allocates, blocks or divides in step() (the sweep's line change is a few
// multiplications), and keeps time as integer ticks.
#pragma once

#include <cstdint>

#include "palp/fw/multisine_synth.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/protocol/messages.hpp"

namespace palp::fw {

namespace detail {
/// Refusal of field `field` (Nak{out_of_range, field_index}).
inline proto::ErrorCode out_of_range(std::uint8_t field, std::uint8_t& field_index) {
  field_index = field;
  return proto::ErrorCode::out_of_range;
}
/// Refusal of the field `Field` names (`out_of_range<&proto::LoadSweep::stop_Hz>(field_index)`):
/// its index comes from the catalogue (proto::field_index_of).
template <auto Field>
proto::ErrorCode out_of_range(std::uint8_t& field_index) {
  return out_of_range(proto::field_index_of<Field>(), field_index);
}
/// Whether |offset_A| + peak_A stays within proto::kProgramMaxCurrent_A.
inline bool peak_within_limit(float offset_A, double peak_A) {
  const double offset = offset_A < 0 ? -static_cast<double>(offset_A) : offset_A;
  return offset + peak_A <= proto::kProgramMaxCurrent_A;
}
}  // namespace detail

/// What a program did in one tick.
struct ProgramTick {
  float current_A = 0.0f;  ///< set-point (when ended: only a contact end's hold current counts)
  bool ended = false;      ///< the program ended at this tick, with `end`
  proto::ProgramEnd end = proto::ProgramEnd::completed;
  bool contact = false;         ///< the contact watch fired at this tick
  bool measuring = false;       ///< sweep: this tick is in its line's measured cycles
  std::uint32_t step = 0;       ///< ProgramStatus.step
  std::uint16_t repetition = 0; ///< ProgramStatus.repetition
};

/// Hold current_A for duration_s (0: until stopped).
class HoldProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadHold& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  void load(const proto::LoadHold& m, std::uint32_t rate_Hz);
  void start(std::int32_t) {}
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out) const;
  std::uint16_t repetitions_done() const { return 0; }

 private:
  float current_A_ = 0.0f;
  std::uint64_t duration_ticks_ = 0;  // 0: until stopped
};

/// Hold hold_current_A and end with ProgramEnd::contact on the first tick where
/// |count - count at start| >= threshold_counts (the firing count is reported; the hold current
/// stays on), or with ProgramEnd::timeout at tick timeout_ticks (ticks 0 ... timeout - 1 are
/// watched) when timeout_s > 0.
class ContactWatchProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadContactWatch& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  void load(const proto::LoadContactWatch& m, std::uint32_t rate_Hz);
  void start(std::int32_t encoder_count) { armed_count_ = encoder_count; }
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out) const;
  std::uint16_t repetitions_done() const { return 0; }

 private:
  float hold_current_A_ = 0.0f;
  std::uint32_t threshold_counts_ = 1;
  std::uint64_t timeout_ticks_ = 0;  // 0: never
  std::int32_t armed_count_ = 0;
};

/// offset_A + amplitude_A sin(2 pi f t) from phase 0, for `cycles` whole cycles (0: until
/// stopped): ticks 0 ... ticks_for_cycles(cycles, increment) - 1. ProgramStatus.step is the
/// cycle index.
class SineProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadSine& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  void load(const proto::LoadSine& m, std::uint32_t rate_Hz);
  void start(std::int32_t);
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out);
  std::uint16_t repetitions_done() const;

 private:
  float offset_A_ = 0.0f, amplitude_A_ = 0.0f;
  std::uint32_t increment_ = 0;
  std::uint32_t cycles_total_ = 0;  // 0: until stopped
  std::uint32_t previous_ahead_ = 0;  // last phase + increment / 2
  std::uint32_t cycles_done_ = 0;
};

/// The staircase ramp of program_schedule.hpp (RampTiming), with the displacement limit:
/// while climbing, on the first tick where |count - count at ProgramStart| >= the limit, the
/// current level L becomes the top of this repetition. If L > 0 its dwell is cut short and the
/// same tick already outputs the next stair: level L - 1 of the unload (which then mirrors the
/// levels reached, L - 1 ... 0), or without unload level 0 of the next repetition. If L = 0 the
/// level keeps its full dwell and the repetition ends there. Every repetition climbs afresh and
/// may turn at another level. ProgramStatus.step is the stair index within the repetition
/// (0, 1, ... in time order), .repetition the repetition index.
class RampProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadRamp& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  void load(const proto::LoadRamp& m, std::uint32_t rate_Hz);
  void start(std::int32_t encoder_count);
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out);
  std::uint16_t repetitions_done() const { return rep_; }

 private:
  bool advance();   // to the next stair; false when the program is over
  bool next_rep();  // false when it was the last
  void set_level(std::uint32_t level);

  proto::RampTiming timing_{};
  float start_A_ = 0.0f, step_A_ = 0.0f;  // step_A_ signed toward stop_A
  std::uint16_t reps_ = 1;
  bool unload_ = true;
  std::uint32_t limit_counts_ = 0;  // 0: none
  // run state
  std::int32_t start_count_ = 0;
  std::uint16_t rep_ = 0;
  std::uint32_t level_ = 0, stair_ = 0;
  bool climbing_ = true, turned_ = false;
  std::uint64_t stair_end_ = 0;  // first tick of the next stair
  float current_A_ = 0.0f;
};

/// The stepped-sine sweep of program_schedule.hpp (SweepPlan): each line restarts at phase 0
/// and runs whole cycles, so the phase is continuous to within one tick's increment at every
/// line change and the host demodulates each line from its own first tick. Line boundaries are
/// found by counting phase wraps. ProgramStatus.step is the line index.
class SweepProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadSweep& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  void load(const proto::LoadSweep& m, std::uint32_t rate_Hz);
  void start(std::int32_t);
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out);
  std::uint16_t repetitions_done() const;  // whole lines done

 private:
  void begin_line();

  proto::SweepPlan plan_{};
  float offset_A_ = 0.0f, amplitude_A_ = 0.0f;
  std::uint32_t line_ = 0;
  proto::SweepLine current_{};
  std::uint32_t tick_ = 0;  // within the line (wraps harmlessly: the phase is mod 2^32 anyway)
  std::uint32_t previous_ahead_ = 0;  // last phase + increment / 2
  std::uint32_t cycles_done_ = 0;
};

/// The periodic multisine (multisine_synth.hpp) for `periods` periods of P ticks (0: until
/// stopped). ProgramStatus.repetition is the period index.
class MultisineProgram {
 public:
  static proto::ErrorCode validate(const proto::LoadMultisine& m, std::uint32_t rate_Hz,
                                   std::uint8_t& field_index);
  /// The lines a valid message describes, as the device runs them.
  static MultisineLines lines_of(const proto::LoadMultisine& m, std::uint32_t rate_Hz);
  void load(const proto::LoadMultisine& m, std::uint32_t rate_Hz);
  void start(std::int32_t);
  void step(std::uint64_t k, std::int32_t encoder_count, ProgramTick& out);
  std::uint16_t repetitions_done() const;
  const MultisineSynth& synth() const { return synth_; }

 private:
  MultisineSynth synth_;
  float offset_A_ = 0.0f, amplitude_A_ = 0.0f;
  std::uint32_t period_ticks_ = 1;
  std::uint16_t periods_ = 0;  // 0: until stopped
  std::uint32_t tick_in_period_ = 0;
  std::uint32_t periods_done_ = 0;
};

}  // namespace palp::fw
