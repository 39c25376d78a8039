// SPDX-License-Identifier: Apache-2.0
// The on-device programs, tick by tick, with known answers: exact timing in ticks, set-points,
// ends, the displacement limit against a synthetic encoder, the contact threshold. The runner's
// life cycle and the validation are in test_program_runner.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "palp/protocol/program_schedule.hpp"
#include "palp/fw/programs.hpp"
#include "palp/fw/waveform.hpp"
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

using proto::ErrorCode;
using proto::ProgramEnd;
using proto::ProgramState;

using namespace palp::fw::test;

using test::kTwoPi;

float level_A(const proto::LoadRamp& m, std::uint32_t level) {
  const float step = m.stop_A < m.start_A ? -m.step_A : m.step_A;
  return m.start_A + step * static_cast<float>(level);
}

// ---- ramp -------------------------------------------------------------------------------------

TEST(ProgramRamp, PaperRampHas251LevelsEndingExactlyOnStop) {
  const proto::RampTiming t = proto::ramp_timing(paper_2d_ramp(), kRate);
  EXPECT_EQ(t.levels, 251u);
  EXPECT_EQ(t.stairs_per_rep, 501u);
  EXPECT_EQ(t.dwell_ticks, 500u);
  EXPECT_EQ(t.ticks_per_rep, 501u * 500u);  // 12.525 s
  EXPECT_EQ(t.total_ticks, 3u * 501u * 500u);
  EXPECT_NEAR(level_A(paper_2d_ramp(), 250), 3.0f, 1e-6f);
  // off the grid, stop_A is not reached: 0.5 -> 3 by 0.3 = 0.5, 0.8, ..., 2.9
  proto::LoadRamp off = paper_2d_ramp();
  off.step_A = 0.3f;
  EXPECT_EQ(proto::ramp_timing(off, kRate).levels, 9u);
  // the 1D ramp of §IV-A at 40 kHz: 100 ms dwell
  proto::LoadRamp one_d = paper_2d_ramp();
  one_d.dwell_s = 0.1f;
  one_d.unload = 0;
  EXPECT_EQ(proto::ramp_timing(one_d, 40000).dwell_ticks, 4000u);
  EXPECT_EQ(proto::ramp_timing(one_d, 40000).ticks_per_rep, 251u * 4000u);
}

TEST(ProgramRamp, EveryTickOfThreeRepetitionsIsOnItsScheduledLevelAndTheEndIsExact) {
  const proto::LoadRamp m = paper_2d_ramp();
  const proto::RampTiming t = proto::ramp_timing(m, kRate);
  ProgramRunner r = loaded(m);
  ASSERT_EQ(r.start(kT0, 0), ErrorCode::ok);
  for (std::uint64_t k = 0; k < t.total_ticks; ++k) {
    const ProgramStep s = r.step(kT0 + k, 0);
    const std::uint32_t level = proto::ramp_level_at(t, k);
    ASSERT_TRUE(s.running) << k;
    ASSERT_NEAR(s.current_A, level_A(m, level), 1e-6f) << "tick " << k;
    ASSERT_EQ(s.repetition, k / t.ticks_per_rep) << k;
    ASSERT_EQ(s.step, (k % t.ticks_per_rep) / t.dwell_ticks) << k;
  }
  // spot checks of the schedule itself
  EXPECT_EQ(proto::ramp_level_at(t, 0), 0u);
  EXPECT_EQ(proto::ramp_level_at(t, 250 * 500), 250u);        // the top, held once
  EXPECT_EQ(proto::ramp_level_at(t, 251 * 500 - 1), 250u);
  EXPECT_EQ(proto::ramp_level_at(t, 251 * 500), 249u);        // the unload starts
  EXPECT_EQ(proto::ramp_level_at(t, 501 * 500 - 1), 0u);      // end of repetition 0 ...
  EXPECT_EQ(proto::ramp_level_at(t, 501 * 500), 0u);          // ... start of repetition 1
  const ProgramStep end = r.step(kT0 + t.total_ticks, 0);
  EXPECT_TRUE(end.finished);
  EXPECT_FALSE(end.running);
  EXPECT_EQ(end.end, ProgramEnd::completed);
  EXPECT_EQ(end.current_A, 0.0f);
  EXPECT_EQ(r.repetitions_done(), 3u);
  EXPECT_EQ(r.state(), ProgramState::finished);
  EXPECT_EQ(r.status(kT0 + t.total_ticks + 99).elapsed_us, t.total_ticks * 50u);
}

TEST(ProgramRamp, WithoutUnloadEachRepetitionClimbsFromStartAgain) {
  proto::LoadRamp m = paper_2d_ramp();
  m.unload = 0;
  m.repetitions = 2;
  ProgramRunner r2 = loaded(m);
  r2.start(kT0, 0);
  ProgramStep s;
  for (std::uint64_t k = 0; k < 251 * 500; ++k) s = r2.step(kT0 + k, 0);
  EXPECT_NEAR(s.current_A, 3.0f, 1e-6f);  // the top, then straight back to the start
  s = r2.step(kT0 + 251 * 500, 0);
  EXPECT_FLOAT_EQ(s.current_A, 0.5f);
  EXPECT_EQ(s.repetition, 1u);
  for (std::uint64_t k = 251 * 500 + 1; k < 2 * 251 * 500; ++k) s = r2.step(kT0 + k, 0);
  EXPECT_TRUE(s.running);
  EXPECT_TRUE(r2.step(kT0 + 2 * 251 * 500, 0).finished);
}

TEST(ProgramRamp, DescendingRampStepsDownToStop) {
  proto::LoadRamp m;
  m.start_A = 1.0f;
  m.stop_A = -1.0f;
  m.step_A = 0.5f;
  m.dwell_s = 0.001f;  // 20 ticks
  m.repetitions = 1;
  m.unload = 1;
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  const float expected[] = {1.0f, 0.5f, 0.0f, -0.5f, -1.0f, -0.5f, 0.0f, 0.5f, 1.0f};
  for (std::uint64_t k = 0; k < 9 * 20; ++k)
    ASSERT_FLOAT_EQ(r.step(kT0 + k, 0).current_A, expected[k / 20]) << k;
  EXPECT_TRUE(r.step(kT0 + 180, 0).finished);
}

// A probe pressing on a linear specimen: the encoder, one tick late, moves 4 counts per 0.01 A
// above 0.5 A, from `origin`, in direction `sign`.
struct LinearSpecimen {
  std::int32_t origin = 5000;
  int sign = 1;
  float last_A = 0.5f;
  std::int32_t count() const {
    return origin + sign * static_cast<std::int32_t>(std::lround((last_A - 0.5f) * 400.0f));
  }
};

TEST(ProgramRamp, DisplacementLimitTurnsRoundAtTheLevelReachedAndMirrorsIt) {
  for (int sign : {1, -1}) {
    proto::LoadRamp m = paper_2d_ramp();
    m.repetitions = 2;
    m.displacement_limit_counts = 100;  // reached at level 25 (0.75 A)
    LinearSpecimen probe;
    probe.sign = sign;
    ProgramRunner r = loaded(m);
    r.start(kT0, probe.count());
    // level 25 starts at tick 25 * 500; the encoder sees it one tick later and the same tick
    // already outputs level 24: the unload mirrors 24 ... 0, each a full dwell
    const std::uint64_t turn = 25 * 500 + 1;
    const std::uint64_t rep_ticks = turn + 25 * 500;
    std::vector<float> got;
    ProgramStep s;
    std::uint64_t k = 0;
    for (; k < 2 * rep_ticks; ++k) {
      s = r.step(kT0 + k, probe.count());
      ASSERT_TRUE(s.running) << k;
      probe.last_A = s.current_A;
      const std::uint64_t kr = k % rep_ticks;
      const std::uint32_t level =
          kr < turn ? static_cast<std::uint32_t>(kr / 500)
                    : 24 - static_cast<std::uint32_t>((kr - turn) / 500);
      ASSERT_NEAR(s.current_A, level_A(m, level), 1e-6f) << "sign " << sign << " tick " << k;
      ASSERT_EQ(s.repetition, k / rep_ticks);
    }
    s = r.step(kT0 + k, probe.count());
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(s.end, ProgramEnd::completed);
    EXPECT_EQ(r.repetitions_done(), 2u);
  }
}

TEST(ProgramRamp, DisplacementLimitAlreadyReachedHoldsOnlyTheStartLevelEachRepetition) {
  proto::LoadRamp m = paper_2d_ramp();
  m.repetitions = 3;
  m.displacement_limit_counts = 50;
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 3 * 500; ++k) {
    const ProgramStep s = r.step(kT0 + k, -60);  // beyond the limit from the first tick
    ASSERT_FLOAT_EQ(s.current_A, 0.5f) << k;
    ASSERT_EQ(s.repetition, k / 500) << k;
  }
  EXPECT_TRUE(r.step(kT0 + 3 * 500, -60).finished);
}

// ---- hold -------------------------------------------------------------------------------------

TEST(ProgramHold, HoldsTheCurrentForExactlyTheDurationInTicks) {
  proto::LoadHold m;
  m.current_A = 1.25f;
  m.duration_s = 0.1f;  // 2000 ticks at 20 kHz
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 2000; ++k) ASSERT_EQ(r.step(kT0 + k, 0).current_A, 1.25f) << k;
  const ProgramStep end = r.step(kT0 + 2000, 0);
  EXPECT_TRUE(end.finished);
  EXPECT_EQ(end.end, ProgramEnd::completed);
  EXPECT_EQ(end.current_A, 0.0f);
  EXPECT_EQ(r.step(kT0 + 2001, 0).current_A, 0.0f);
  EXPECT_EQ(proto::ticks_from_seconds(1e-7f, kRate), 1u);  // a positive duration is at least a tick
}

TEST(ProgramHold, ZeroDurationHoldsUntilStoppedThenZeroAtOnce) {
  proto::LoadHold m;
  m.current_A = -0.75f;
  m.duration_s = 0.0f;
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 2000000; ++k) ASSERT_TRUE(r.step(kT0 + k, 0).running);
  EXPECT_TRUE(r.stop(kT0 + 2000000));
  EXPECT_EQ(r.end(), ProgramEnd::stopped_by_host);
  const ProgramStep s = r.step(kT0 + 2000000, 0);  // the same tick
  EXPECT_EQ(s.current_A, 0.0f);
  EXPECT_FALSE(s.running);
  EXPECT_FALSE(s.finished);  // the stop was reported by stop()'s return value
  EXPECT_FALSE(r.stop(kT0 + 2000001));
}

// ---- sine -------------------------------------------------------------------------------------

TEST(ProgramSine, ValuesAtKnownTicksMatchTheSineWithinTheTableError) {
  ProgramRunner r = loaded(sine_5Hz(0));
  r.start(kT0, 0);
  const std::uint32_t inc = proto::phase_increment(5.0f, kRate);
  for (std::uint64_t k = 0; k < 40000; ++k) {
    const float i = r.step(kT0 + k, 0).current_A;
    const double turns = static_cast<double>((k * inc) % (1ull << 32)) / 4294967296.0;
    const double realised = 1.0 + 0.1 * std::sin(kTwoPi * turns);
    const double nominal = 1.0 + 0.1 * std::sin(kTwoPi * 5.0 * k / kRate);
    ASSERT_NEAR(i, realised, 0.1 * kSineMaxError + 2e-7) << k;
    ASSERT_NEAR(i, nominal, 0.1 * kSineMaxError + 0.1 * kTwoPi * 0.5 / 4294967296.0 * k + 2e-7);
    if (k == 0) {
      EXPECT_EQ(i, 1.0f);  // starts at phase 0
    } else if (k == 1000) {
      EXPECT_NEAR(i, 1.1f, 1e-6f);  // a quarter cycle at 5 Hz
    } else if (k == 3000) {
      EXPECT_NEAR(i, 0.9f, 1e-6f);  // three quarters
    }
  }
}

TEST(ProgramSine, RunsWholeCyclesAndEndsOnTheTickTheLastCycleCompletes) {
  ProgramRunner r = loaded(sine_5Hz(3));
  r.start(kT0, 0);
  const std::uint64_t ticks = proto::ticks_for_cycles(3, proto::phase_increment(5.0f, kRate));
  EXPECT_EQ(ticks, 12000u);  // 3 cycles of 4000 ticks (the realised frequency is a hair higher)
  for (std::uint64_t k = 0; k < ticks; ++k) {
    const ProgramStep s = r.step(kT0 + k, 0);
    ASSERT_TRUE(s.running) << k;
    ASSERT_EQ(s.step, k / 4000) << k;  // the cycle index
  }
  const ProgramStep end = r.step(kT0 + ticks, 0);
  EXPECT_TRUE(end.finished);
  EXPECT_EQ(end.current_A, 0.0f);
  EXPECT_EQ(r.repetitions_done(), 3u);
}

// ---- sweep ------------------------------------------------------------------------------------

proto::LoadSweep paper_sweep() {  // §IV-B: 1 A + 0.1 A, 2 ... 20 Hz by 0.05 Hz
  proto::LoadSweep m;  // catalogue defaults: settle max(3 cycles, 1.2 s), measure 5 cycles
  return m;
}

// Runs a sweep tick by tick and checks each line's first tick, settle end and output at its
// first tick (phase 0) against the schedule; returns the total ticks.
std::uint64_t run_sweep_against_schedule(const proto::LoadSweep& m, std::uint32_t rate) {
  const proto::SweepPlan p = proto::sweep_plan(m, rate);
  ProgramRunner r = loaded(m, rate);
  r.start(kT0, 0);
  std::uint64_t k = 0;
  for (std::uint32_t j = 0; j < p.lines; ++j) {
    const proto::SweepLine line = proto::sweep_line(p, j);
    const std::uint64_t settle = proto::sweep_settle_ticks(line);
    const std::uint64_t ticks = proto::sweep_line_ticks(line);
    for (std::uint64_t t = 0; t < ticks; ++t, ++k) {
      const ProgramStep s = r.step(kT0 + k, 0);
      if (s.step != j || !s.running || s.measuring != (t >= settle)) {
        ADD_FAILURE() << "line " << j << " tick " << t << " step " << s.step << " measuring "
                      << s.measuring << " settle " << settle;
        return k;
      }
      if (t == 0 && s.current_A != m.offset_A) {
        ADD_FAILURE() << "line " << j << " does not start at phase 0";
        return k;
      }
    }
  }
  const ProgramStep end = r.step(kT0 + k, 0);
  EXPECT_TRUE(end.finished);
  EXPECT_EQ(end.end, ProgramEnd::completed);
  EXPECT_EQ(r.repetitions_done(), p.lines);
  EXPECT_EQ(k, proto::sweep_total_ticks(p));
  return k;
}

TEST(ProgramSweep, PaperSweepHas361LinesAndLasts687sOfWholeCycles) {
  const proto::SweepPlan p = proto::sweep_plan(paper_sweep(), kRate);
  EXPECT_EQ(p.lines, 361u);
  // independent reference: sum over f = 2 + 0.05 j of (max(3, ceil(1.2 f)) + 5) / f seconds
  double reference_s = 0.0;
  for (int j = 0; j < 361; ++j) {
    const double f = 2.0 + 0.05 * j;
    const double settle = std::fmax(3.0, std::ceil(std::round(1.2 * f * 1e6) / 1e6));
    reference_s += (settle + 5.0) / f;
  }
  const std::uint64_t ticks = proto::sweep_total_ticks(p);
  std::printf("paper sweep: %llu ticks = %.5f s at 20 kHz (reference %.5f s)\n",
              static_cast<unsigned long long>(ticks), ticks / 20000.0, reference_s);
  EXPECT_EQ(ticks, 13743184u);  // 687.1592 s
  EXPECT_NEAR(ticks / 20000.0, reference_s, 361 * 0.5 / 20000.0);  // half a tick per line
  // (the "about 665 s" of a settle that is max(3 cycles, 1.2 s) without whole cycles is
  //  666.38 s; rounding each settle up to whole cycles adds 20.8 s)
}

TEST(ProgramSweep, PaperSweepRunsTickByTickOnItsScheduleAt20And40kHz) {
  EXPECT_EQ(run_sweep_against_schedule(paper_sweep(), 20000), 13743184u);
  const std::uint64_t ticks_40k = run_sweep_against_schedule(paper_sweep(), 40000);
  EXPECT_NEAR(ticks_40k / 40000.0, 13743184 / 20000.0, 361 / 20000.0);
}

TEST(ProgramSweep, SettleCoversSettleMinInWholeCyclesAndAtLeastSettleCycles) {
  const proto::SweepPlan p = proto::sweep_plan(paper_sweep(), kRate);
  EXPECT_EQ(proto::sweep_line(p, 0).settle_cycles, 3u);     // 2 Hz: 1.2 s is 2.4 cycles -> 3
  EXPECT_EQ(proto::sweep_line(p, 10).settle_cycles, 3u);    // 2.5 Hz: exactly 3.0 cycles
  EXPECT_EQ(proto::sweep_line(p, 11).settle_cycles, 4u);    // 2.55 Hz: 3.06 -> 4
  EXPECT_EQ(proto::sweep_line(p, 160).settle_cycles, 12u);  // 10 Hz: exactly 12
  EXPECT_EQ(proto::sweep_line(p, 161).settle_cycles, 13u);  // 10.05 Hz: 12.06 -> 13
  EXPECT_EQ(proto::sweep_line(p, 360).settle_cycles, 24u);  // 20 Hz
  EXPECT_EQ(proto::sweep_line(p, 360).cycles, 29u);
  EXPECT_EQ(proto::sweep_settle_ticks(proto::sweep_line(p, 0)), 30000u);  // 3 cycles of 2 Hz
  EXPECT_EQ(proto::sweep_line_ticks(proto::sweep_line(p, 0)), 80000u);    // 8 cycles = 4 s
  EXPECT_EQ(proto::sweep_line_ticks(proto::sweep_line(p, 360)), 29000u);  // 29 cycles of 20 Hz
}

TEST(ProgramSweep, SingleLineSweepFromStartEqualsStop) {
  proto::LoadSweep m;
  m.start_Hz = m.stop_Hz = 10.0f;
  m.settle_cycles = 1;
  m.settle_min_s = 0.0f;
  m.measure_cycles = 2;
  EXPECT_EQ(run_sweep_against_schedule(m, kRate), 6000u);  // 3 cycles of 2000 ticks
}

// ---- multisine --------------------------------------------------------------------------------

TEST(ProgramMultisine, RunsWholePeriodsAndReportsThePeriodIndex) {
  proto::LoadMultisine m;  // 90 lines, 0.05 Hz: periods of 400000 ticks
  m.periods = 2;
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 800000; ++k) {
    const ProgramStep s = r.step(kT0 + k, 0);
    ASSERT_TRUE(s.running) << k;
    ASSERT_EQ(s.repetition, k / 400000) << k;
    ASSERT_NEAR(s.current_A, 1.0f, 0.9f + 1e-4f);  // offset 1 A, 90 lines of 0.01 A
  }
  EXPECT_TRUE(r.step(kT0 + 800000, 0).finished);
  EXPECT_EQ(r.repetitions_done(), 2u);
}

TEST(ProgramMultisine, OutputIsOffsetPlusAmplitudeTimesTheUnitSum) {
  proto::LoadMultisine m;
  m.offset_A = -0.5f;
  m.line_amplitude_A = 0.02f;
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  MultisineSynth reference;
  reference.configure(MultisineProgram::lines_of(m, kRate));
  for (std::uint64_t k = 0; k < 10000; ++k)
    ASSERT_FLOAT_EQ(r.step(kT0 + k, 0).current_A, -0.5f + 0.02f * reference.step()) << k;
}

TEST(ProgramMultisine, FourHundredLinesCostFiftyLineEvaluationsInEveryTick) {
  ProgramRunner r = loaded(four_hundred_line_multisine());
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 100000; ++k) {
    r.step(kT0 + k, 0);
    ASSERT_EQ(r.multisine()->synth().lines_last_step(), 50u) << k;
  }
}

// ---- contact watch ----------------------------------------------------------------------------

TEST(ProgramContact, FiresAtExactlyTheThresholdNotOneCountBeforeInBothDirections) {
  for (int sign : {1, -1}) {
    proto::LoadContactWatch m;  // 0.5 A, 200 counts, no timeout
    ProgramRunner r = loaded(m);
    const std::int32_t armed = 12345;
    r.start(kT0, armed);
    for (std::int32_t moved = 0; moved < 200; ++moved) {
      const ProgramStep s = r.step(kT0 + moved, armed + sign * moved);
      ASSERT_TRUE(s.running) << moved;
      ASSERT_FALSE(s.contact) << moved;
      ASSERT_EQ(s.current_A, 0.5f);
    }
    const ProgramStep s = r.step(kT0 + 200, armed + sign * 200);
    EXPECT_TRUE(s.contact);
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(s.end, ProgramEnd::contact);
    EXPECT_EQ(s.contact_count, armed + sign * 200);
    EXPECT_EQ(r.armed_count(), armed);
    EXPECT_EQ(s.current_A, 0.5f);  // the hold current stays on: the controller decides
    EXPECT_TRUE(r.contact_latched());
    EXPECT_EQ(r.step(kT0 + 201, armed).current_A, 0.5f);
    EXPECT_FALSE(r.stop(kT0 + 202));  // nothing runs, but the hold is dropped
    EXPECT_EQ(r.step(kT0 + 203, armed).current_A, 0.0f);
  }
}

TEST(ProgramContact, TimeoutEndsAfterExactlyTheTimeoutWithZeroCurrent) {
  proto::LoadContactWatch m;
  m.hold_current_A = 0.4f;
  m.timeout_s = 0.5f;  // 10000 ticks
  ProgramRunner r = loaded(m);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 10000; ++k) ASSERT_TRUE(r.step(kT0 + k, 199).running) << k;
  const ProgramStep s = r.step(kT0 + 10000, 500);  // too late: the watch covered 0 ... 9999
  EXPECT_TRUE(s.finished);
  EXPECT_EQ(s.end, ProgramEnd::timeout);
  EXPECT_FALSE(s.contact);
  EXPECT_EQ(s.current_A, 0.0f);
  EXPECT_FALSE(r.contact_latched());
}

}  // namespace
}  // namespace palp::fw
