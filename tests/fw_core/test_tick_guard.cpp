// SPDX-License-Identifier: Apache-2.0
// The command hand-off (controller.hpp, TickGuard): receive() changes the tick's state only inside
// the board's guard, synthesises a Load*'s program outside it, and answers exactly as without a
// guard. A recording guard fingerprints the tick's state (every member tick() reads or writes) at
// each hold and release: what changed between a release and the next hold changed while a tick
// could have run.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "controller_bench.hpp"

namespace palp::fw {

/// Friend of Controller and ProgramRunner: the bytes of the tick's state, and of the program
/// slots (the active one and the staging one alike).
struct TickStateProbe {
  struct Fnv {
    std::uint64_t h = 0xCBF29CE484222325ull;
    template <class T>
    Fnv& operator<<(const T& v) {
      const auto* p = reinterpret_cast<const unsigned char*>(&v);
      for (std::size_t k = 0; k < sizeof v; ++k) h = (h ^ p[k]) * 0x100000001B3ull;
      return *this;
    }
  };
  // what step() reads and writes: the active slot and the runner's own fields, not the staging
  static Fnv& runner(Fnv& f, const ProgramRunner& r) {
    return f << r.slots_[r.active_] << r.active_ << r.kind_ << r.state_ << r.end_ << r.rate_Hz_
             << r.start_tick_ << r.end_tick_ << r.armed_count_ << r.contact_latched_
             << r.rest_current_A_ << r.step_ << r.repetition_;
  }
  static std::uint64_t tick_state(const Controller& c) {
    Fnv f;
    f << c.params_ << c.calibration_ << c.loop_ << c.encoder_ << c.pressure_ << c.safety_
      << c.monitor_ << c.streamer_ << c.tick_ << c.time_base_ << c.encoder_started_ << c.i_set_A_
      << c.i_meas_A_ << c.v_cmd_V_ << c.clamped_ << c.contact_line_ << c.contact_line_until_tick_
      << c.samples_ << c.events_;
    return runner(f, c.programs_).h;
  }
  static std::uint64_t live_program(const Controller& c) {
    Fnv f;
    return runner(f, c.programs_).h;
  }
  static std::uint64_t program_slots(const Controller& c) {
    return (Fnv{} << c.programs_.slots_).h;
  }
};

namespace {

using namespace palp::proto;
using test::Bench;

/// A TickGuard that checks the hand-off while receive() runs (arm() before, finish() after;
/// violations add up over a test, the counters are per request).
struct GuardRecorder {
  const Controller* c = nullptr;
  bool held = false;
  int holds = 0;
  int changed_inside = 0;      // held sections that changed the tick's state
  int program_adopted = 0;     // held sections that changed the program the tick runs
  int slots_inside = 0;        // held sections that wrote a program slot
  int slots_outside = 0;       // stretches outside the guard that wrote a program slot
  std::vector<std::string> violations;
  std::uint64_t state = 0, slots = 0, live = 0;

  TickGuard guard() { return {&on_hold, &on_release, this}; }

  void arm() {
    held = false;
    holds = changed_inside = program_adopted = slots_inside = slots_outside = 0;
    snapshot();
  }
  void finish() {
    if (held) violations.push_back("receive() returned with the guard held");
    outside_ends();
  }

 private:
  void snapshot() {
    state = TickStateProbe::tick_state(*c);
    slots = TickStateProbe::program_slots(*c);
    live = TickStateProbe::live_program(*c);
  }
  // the end of a stretch outside the guard: nothing of the tick's may have changed
  void outside_ends() {
    if (TickStateProbe::tick_state(*c) != state)
      violations.push_back("the tick's state changed outside the guard");
    if (TickStateProbe::program_slots(*c) != slots) ++slots_outside;
  }
  static void on_hold(void* ctx) {
    auto& r = *static_cast<GuardRecorder*>(ctx);
    if (r.held) r.violations.push_back("hold() while held");
    r.outside_ends();
    r.held = true;
    ++r.holds;
    r.snapshot();
  }
  static void on_release(void* ctx) {
    auto& r = *static_cast<GuardRecorder*>(ctx);
    if (!r.held) r.violations.push_back("release() while not held");
    r.held = false;
    if (TickStateProbe::tick_state(*r.c) != r.state) ++r.changed_inside;
    if (TickStateProbe::live_program(*r.c) != r.live) ++r.program_adopted;
    if (TickStateProbe::program_slots(*r.c) != r.slots) ++r.slots_inside;
    r.snapshot();
  }
};

struct GuardedBench : Bench {
  GuardRecorder rec;
  GuardedBench() {
    rec.c = &c_;
    c_.set_tick_guard(rec.guard());
  }
  /// Sends m through receive() with the recorder armed (ticks ran since the last request).
  template <class M>
  void send(const M& m, u16 seq = 1) {
    rec.arm();
    Bench::send(m, seq);
    rec.finish();
  }
  /// send(), then the recorder's findings about this request alone.
  template <class M>
  const GuardRecorder& checked(const M& m, u16 seq = 1) {
    rec.violations.clear();
    send(m, seq);
    return rec;
  }
};

LoadMultisine four_hundred_lines() {
  LoadMultisine ms;  // the tick-cost image's: 400 lines, 0.25 ... 100 Hz
  ms.offset_A = 1.0f;
  ms.fundamental_Hz = 0.25f;
  ms.line_first = 1;
  ms.line_last = 400;
  ms.line_step = 1;
  ms.line_amplitude_A = 0.0005f;
  ms.phase_mode = PhaseMode::schroeder;
  ms.periods = 0;
  return ms;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "; ";
  return s;
}

// Every request type, with its defaults, idle and then while a program and the stream run (the
// busy refusals): the tick's state never changes outside a held section, and every request is
// served in held sections that pair up.
TEST(TickGuard, EveryRequestChangesTheTicksStateOnlyInsideTheGuard) {
  for (const bool running : {false, true}) {
    GuardedBench b;
    if (running) {
      b.send(LoadHold{0.3f, 0.0f}, 1);
      b.send(ProgramStart{}, 2);
      b.send(StreamStart{}, 3);
      b.run_ticks(100);
    }
    for_each_message_type([&](auto m) {
      using M = decltype(m);
      if constexpr (std::is_same_v<M, Hello>) m = Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "again"};
      const GuardRecorder& r = b.checked(m, 7);
      EXPECT_TRUE(r.violations.empty()) << M::kName << (running ? " (running): " : ": ")
                                        << joined(r.violations);
      EXPECT_GE(r.holds, 1) << M::kName;
      b.run_ticks(3);
    });
  }
}

// The fingerprint sees what each state-changing request does, so the test above can fail.
TEST(TickGuard, EachStateChangingRequestChangesTheTicksStateInsideAHeldSection) {
  GuardedBench b;
  SetParams p;
  p.travel_max_counts = 9000;
  EXPECT_GE(b.checked(p).changed_inside, 1) << "SetParams";
  SetCalibration cal = fields_as<SetCalibration>(to_proto(CalibrationData{}));
  cal.current_gain = 1.01f;
  EXPECT_GE(b.checked(cal).changed_inside, 1) << "SetCalibration";
  b.pump();
  EXPECT_EQ(b.last<Calibration>().current_gain, 1.01f);
  EXPECT_EQ(b.checked(LoadHold{0.3f, 0.0f}).program_adopted, 1) << "LoadHold";
  EXPECT_GE(b.checked(StreamConfigure{kAllChannels, 4, 40}).changed_inside, 1) << "StreamConfigure";
  EXPECT_GE(b.checked(StreamStart{}).changed_inside, 1) << "StreamStart";
  EXPECT_GE(b.checked(ProgramStart{}).changed_inside, 1) << "ProgramStart";
  b.run_ticks(40);
  EXPECT_GE(b.checked(ProgramStop{}).changed_inside, 1) << "ProgramStop";
  EXPECT_GE(b.checked(StreamStop{}).changed_inside, 1) << "StreamStop";
  EXPECT_TRUE(b.rec.violations.empty()) << joined(b.rec.violations);
}

// A 400-line multisine (~25 000 instructions of synthesis) is written into the staging slot with
// the tick free, and the runner takes it over in one held section that writes no slot (an index
// flip).
TEST(TickGuard, AFourHundredLineMultisineIsSynthesisedOutsideTheGuardAndAdoptedInOneHeldSection) {
  GuardedBench b;
  const GuardRecorder& r = b.checked(four_hundred_lines(), 5);
  EXPECT_TRUE(r.violations.empty()) << joined(r.violations);
  EXPECT_EQ(r.slots_outside, 1);  // the synthesis, between the busy check and the adoption
  EXPECT_EQ(r.slots_inside, 0);
  EXPECT_EQ(r.holds, 2);  // the busy check, then the adoption
  EXPECT_EQ(r.program_adopted, 1);
  b.pump();
  EXPECT_EQ(b.last<Ack>().request_id, static_cast<u8>(MessageId::LoadMultisine));
  b.send(ProgramStart{}, 6);
  b.run_ticks(2000);
  EXPECT_NEAR(b.i_A_, 1.0, 0.2);  // the adopted multisine runs about its 1 A offset
  EXPECT_FALSE(b.c_.faulted());
}

// A refused load changes nothing the tick runs, and its answer is the one it always was.
TEST(TickGuard, ARefusedLoadLeavesTheLiveProgramAndIsAnsweredAsBefore) {
  GuardedBench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  LoadMultisine bad = four_hundred_lines();
  bad.line_last = 600;  // above 125 Hz
  const GuardRecorder& r = b.checked(bad, 2);
  EXPECT_TRUE(r.violations.empty()) << joined(r.violations);
  EXPECT_EQ(r.program_adopted, 0);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::out_of_range);
  b.send(GetProgramStatus{}, 3);
  b.pump();
  EXPECT_EQ(b.last<ProgramStatus>().kind, ProgramKind::hold);
}

/// The device's bytes since the last call.
std::vector<u8> device_bytes(Controller& c) {
  c.service();
  std::vector<u8> out;
  u8 buf[4096];
  std::size_t n;
  while ((n = c.transmit(buf, sizeof buf)) > 0) out.insert(out.end(), buf, buf + n);
  return out;
}

// One session on two controllers, one with the guard: every byte the device sends is the same.
TEST(TickGuard, ADeviceWithTheGuardSendsTheSameBytesAsOneWithout) {
  Bench plain;
  GuardedBench guarded;
  std::vector<u8> a, b;
  const auto both = [&](const auto& m, u16 seq, int ticks) {
    plain.send(m, seq);
    guarded.send(m, seq);
    plain.run_ticks(ticks);
    guarded.run_ticks(ticks);
  };
  // run_ticks() pumps the frames into got_; compare those, header and payload
  both(StreamConfigure{kAllChannels, 4, 40}, 1, 0);
  both(LoadContactWatch{0.5f, 200, 0.0f}, 2, 0);
  both(StreamStart{}, 3, 0);
  plain.encoder_per_tick_ = guarded.encoder_per_tick_ = 1;
  both(ProgramStart{}, 4, 400);
  both(four_hundred_lines(), 5, 10);
  both(LoadRamp{}, 6, 10);
  both(GetStatus{}, 7, 10);
  both(ProgramStart{}, 8, 300);
  both(LoadHold{}, 9, 0);  // busy: the ramp runs
  both(ProgramStop{}, 10, 10);
  both(GetProgramStatus{}, 11, 0);
  both(SetParams{}, 12, 0);  // busy: the stream runs
  both(StreamStop{}, 13, 10);
  both(GetHealth{}, 14, 0);
  ASSERT_EQ(plain.got_.size(), guarded.got_.size());
  for (std::size_t k = 0; k < plain.got_.size(); ++k) {
    EXPECT_EQ(plain.got_[k].name, guarded.got_[k].name) << k;
    EXPECT_EQ(plain.got_[k].header.seq, guarded.got_[k].header.seq) << k;
    EXPECT_EQ(plain.got_[k].payload, guarded.got_[k].payload) << k << " " << plain.got_[k].name;
  }
  EXPECT_GE(plain.all<SampleBatch>().size(), 4u);
  EXPECT_EQ(plain.all<Nak>().size(), 2u);
  EXPECT_TRUE(guarded.rec.violations.empty()) << joined(guarded.rec.violations);
  EXPECT_TRUE(device_bytes(plain.c_).empty());
}

// The adoption keeps the runtime rest state exactly as a load into the live runner did: after a
// contact the hold current stays on and contact_latched stays set until the next ProgramStart.
TEST(TickGuard, ALoadAfterAContactKeepsTheContactHoldAndItsLatchUntilTheNextStart) {
  GuardedBench b;
  b.send(LoadContactWatch{0.5f, 200, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.encoder_per_tick_ = 1;
  b.run_ticks(400);
  ASSERT_EQ(b.last<EventProgramFinished>().end, ProgramEnd::contact);
  b.encoder_ = static_cast<int>(b.c_.ticks());  // the coil stops where it touched
  b.encoder_per_tick_ = 0;
  b.send(LoadHold{0.3f, 0.0f}, 3);
  b.run_ticks(200);
  b.send(GetStatus{}, 4);
  b.pump();
  const auto latched = 1u << static_cast<unsigned>(StatusBit::contact_latched);
  Status s = b.last<Status>();
  EXPECT_EQ(s.program_kind, ProgramKind::hold);
  EXPECT_EQ(s.program_state, ProgramState::loaded);
  EXPECT_EQ(s.i_cmd_A, 0.5f);  // the contact watch's hold current, still on
  EXPECT_NE(s.status_bits & latched, 0u);
  b.send(ProgramStart{}, 5);
  b.run_ticks(10);
  b.send(GetStatus{}, 6);
  b.pump();
  s = b.last<Status>();
  EXPECT_EQ(s.i_cmd_A, 0.3f);
  EXPECT_EQ(s.status_bits & latched, 0u);
  EXPECT_TRUE(b.rec.violations.empty()) << joined(b.rec.violations);
}

TEST(TickGuard, ALoadWhileAProgramRunsIsRefusedBusyNamingItWithoutTouchingEitherRunner) {
  GuardedBench b;
  b.send(LoadSine{1.0f, 0.1f, 5.0f, 0}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(10);
  b.clear();
  const GuardRecorder& r = b.checked(four_hundred_lines(), 3);
  EXPECT_EQ(r.holds, 1);
  EXPECT_EQ(r.slots_outside, 0);
  EXPECT_EQ(r.slots_inside, 0);
  EXPECT_EQ(r.program_adopted, 0);
  b.pump();
  const Nak n = b.last<Nak>();
  EXPECT_EQ(n.error, ErrorCode::busy);
  EXPECT_EQ(n.field_index, 255);
  EXPECT_EQ(n.detail, static_cast<std::int32_t>(ProgramKind::sine));
}

}  // namespace
}  // namespace palp::fw
