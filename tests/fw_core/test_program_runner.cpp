// SPDX-License-Identifier: Apache-2.0
// The program runner's life cycle (load, start, stop, fault, restart, status) and the
// validation of every Load* message: refusals name the offending field as Nak does.
#include <gtest/gtest.h>

#include <cmath>

#include "palp/protocol/program_schedule.hpp"
#include "palp/fw/programs.hpp"
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

using namespace palp::fw::test;
using proto::ErrorCode;
using proto::ProgramEnd;
using proto::ProgramState;

// ---- the runner -------------------------------------------------------------------------------

TEST(ProgramRunner, StopMidRampEndsStoppedByHostWithZeroCurrentAtOnce) {
  ProgramRunner r = loaded(paper_2d_ramp());
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 260000; ++k) r.step(kT0 + k, 0);  // into repetition 1
  EXPECT_TRUE(r.stop(kT0 + 260000));
  EXPECT_EQ(r.state(), ProgramState::finished);
  EXPECT_EQ(r.end(), ProgramEnd::stopped_by_host);
  EXPECT_EQ(r.repetitions_done(), 1u);
  const ProgramStep s = r.step(kT0 + 260000, 0);
  EXPECT_EQ(s.current_A, 0.0f);
  EXPECT_FALSE(s.running);
  const proto::ProgramStatus st = r.status(kT0 + 300000);
  EXPECT_EQ(st.state, ProgramState::finished);
  EXPECT_EQ(st.end, ProgramEnd::stopped_by_host);
  EXPECT_EQ(st.elapsed_us, 260000u * 50u);
  EXPECT_EQ(st.repetition, 1u);
  EXPECT_EQ(st.step, (259999u - 250500u) / 500u);
}

TEST(ProgramRunner, FaultAbortEndsWithFaultAndZeroCurrent) {
  ProgramRunner r = loaded(sine_5Hz(0));
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 1234; ++k) r.step(kT0 + k, 0);
  EXPECT_TRUE(r.abort_fault(kT0 + 1234));
  EXPECT_EQ(r.end(), ProgramEnd::fault);
  EXPECT_EQ(r.step(kT0 + 1234, 0).current_A, 0.0f);
  EXPECT_FALSE(r.abort_fault(kT0 + 1235));
}

TEST(ProgramRunner, LifeCycleRefusalsAndRestart) {
  ProgramRunner r;
  EXPECT_EQ(r.start(kT0, 0), ErrorCode::no_program);
  EXPECT_EQ(r.step(kT0, 0).current_A, 0.0f);
  std::uint8_t field = 0;
  proto::LoadHold hold;
  hold.current_A = 0.3f;
  hold.duration_s = 0.001f;  // 20 ticks
  ASSERT_EQ(r.load(hold, kRate, field), ErrorCode::ok);
  EXPECT_EQ(r.state(), ProgramState::loaded);
  EXPECT_EQ(r.kind(), proto::ProgramKind::hold);
  ASSERT_EQ(r.start(kT0, 0), ErrorCode::ok);
  EXPECT_EQ(r.start(kT0, 0), ErrorCode::busy);
  EXPECT_EQ(r.load(hold, kRate, field), ErrorCode::busy);
  EXPECT_EQ(field, 255u);
  for (std::uint64_t k = 0; k <= 20; ++k) r.step(kT0 + k, 0);
  EXPECT_EQ(r.state(), ProgramState::finished);
  // a finished program stays loaded and runs again from its tick 0
  ASSERT_EQ(r.start(kT0 + 500, 0), ErrorCode::ok);
  EXPECT_EQ(r.step(kT0 + 500, 0).current_A, 0.3f);
  EXPECT_EQ(r.status(kT0 + 510).elapsed_us, 500u);
}

TEST(ProgramRunner, RefusedLoadKeepsThePreviousProgram) {
  ProgramRunner r = loaded(sine_5Hz(2));
  proto::LoadSweep bad;
  bad.start_Hz = 30.0f;  // above stop_Hz
  std::uint8_t field = 0;
  EXPECT_EQ(r.load(bad, kRate, field), ErrorCode::out_of_range);
  EXPECT_EQ(field, 3u);
  EXPECT_EQ(r.kind(), proto::ProgramKind::sine);
  EXPECT_EQ(r.state(), ProgramState::loaded);
}

TEST(ProgramRunner, AStagedAndAdoptedProgramRunsTickForTickAsALoadedOne) {
  proto::LoadMultisine m;  // the default 90 lines
  ProgramRunner direct = loaded(m);
  ProgramRunner r = loaded(sine_5Hz(1));
  std::uint8_t field = 0;
  ASSERT_EQ(r.stage(m, kRate, field), ErrorCode::ok);
  EXPECT_EQ(r.kind(), proto::ProgramKind::sine);  // staged, not yet loaded
  EXPECT_EQ(r.staged_kind(), proto::ProgramKind::multisine);
  ASSERT_EQ(r.adopt_staged(), ErrorCode::ok);
  EXPECT_EQ(r.kind(), proto::ProgramKind::multisine);
  EXPECT_EQ(r.state(), ProgramState::loaded);
  EXPECT_EQ(r.staged_kind(), proto::ProgramKind::none);
  EXPECT_EQ(r.adopt_staged(), ErrorCode::no_program);  // nothing staged twice
  ASSERT_EQ(direct.start(kT0, 0), ErrorCode::ok);
  ASSERT_EQ(r.start(kT0, 0), ErrorCode::ok);
  for (std::uint64_t k = 0; k < 20000; ++k)
    ASSERT_EQ(r.step(kT0 + k, 0).current_A, direct.step(kT0 + k, 0).current_A) << k;
}

TEST(ProgramRunner, StagingWhileAProgramRunsLeavesItRunningAndTheAdoptionWaitsForItsEnd) {
  ProgramRunner reference = loaded(sine_5Hz(1));  // 4000 ticks
  ProgramRunner r = loaded(sine_5Hz(1));
  reference.start(kT0, 0);
  r.start(kT0, 0);
  for (std::uint64_t k = 0; k < 100; ++k)
    ASSERT_EQ(r.step(kT0 + k, 0).current_A, reference.step(kT0 + k, 0).current_A) << k;
  std::uint8_t field = 0;
  ASSERT_EQ(r.stage(four_hundred_line_multisine(), kRate, field), ErrorCode::ok);
  EXPECT_EQ(r.adopt_staged(), ErrorCode::busy);
  for (std::uint64_t k = 100; k <= 4000; ++k)
    ASSERT_EQ(r.step(kT0 + k, 0).current_A, reference.step(kT0 + k, 0).current_A) << k;
  ASSERT_EQ(r.state(), ProgramState::finished);
  EXPECT_EQ(r.adopt_staged(), ErrorCode::ok);
  EXPECT_EQ(r.kind(), proto::ProgramKind::multisine);
}

TEST(ProgramRunner, AdoptionKeepsAContactHoldAndItsLatchUntilTheNextStart) {
  proto::LoadContactWatch watch;  // 0.5 A, 200 counts
  ProgramRunner r = loaded(watch);
  r.start(kT0, 0);
  r.step(kT0, 200);  // contact at once
  ASSERT_TRUE(r.contact_latched());
  proto::LoadHold hold;
  hold.current_A = 0.3f;
  std::uint8_t field = 0;
  ASSERT_EQ(r.stage(hold, kRate, field), ErrorCode::ok);
  ASSERT_EQ(r.adopt_staged(), ErrorCode::ok);
  EXPECT_TRUE(r.contact_latched());
  EXPECT_EQ(r.rest_current_A(), 0.5f);
  EXPECT_EQ(r.end(), ProgramEnd::contact);
  EXPECT_EQ(r.step(kT0 + 1, 200).current_A, 0.5f);
  ASSERT_EQ(r.start(kT0 + 2, 200), ErrorCode::ok);
  EXPECT_FALSE(r.contact_latched());
  EXPECT_EQ(r.step(kT0 + 2, 200).current_A, 0.3f);
}

// ---- validation -------------------------------------------------------------------------------

TEST(ProgramValidation, CatalogueRangesAreCheckedFirstAndNameTheField) {
  proto::LoadRamp ramp = paper_2d_ramp();
  ramp.step_A = 0.0f;
  EXPECT_EQ(refused_field(ramp), 2u);
  proto::LoadSine sine = sine_5Hz(1);
  sine.frequency_Hz = std::nanf("");
  EXPECT_EQ(refused_field(sine), 2u);
  proto::LoadMultisine ms;
  ms.phase_seed = 0;
  EXPECT_EQ(refused_field(ms), 7u);
  proto::LoadContactWatch cw;
  cw.threshold_counts = 0;
  EXPECT_EQ(refused_field(cw), 1u);
}

TEST(ProgramValidation, RampStepThatCannotReachStopIsStepA) {
  proto::LoadRamp m = paper_2d_ramp();
  m.step_A = 3.0f;  // 0.5 + 3 > 3
  EXPECT_EQ(refused_field(m), 2u);
  m.step_A = 2.5f;  // exactly reaches stop: two levels
  EXPECT_EQ(proto::ramp_timing(m, kRate).levels, 2u);
  loaded(m);
  m.stop_A = m.start_A;  // a one-level ramp is fine
  EXPECT_EQ(proto::ramp_timing(m, kRate).levels, 1u);
  loaded(m);
}

TEST(ProgramValidation, SweepStartAboveStopIsStopHzAndUnreachableStopIsStepHz) {
  proto::LoadSweep m;
  m.start_Hz = 20.5f;
  EXPECT_EQ(refused_field(m), 3u);
  m.start_Hz = 2.0f;
  m.step_Hz = 18.5f;
  EXPECT_EQ(refused_field(m), 4u);
  m.amplitude_A = 3.5f;  // 1 + 3.5 A > 4 A
  m.step_Hz = 0.05f;
  EXPECT_EQ(refused_field(m), 1u);
}

TEST(ProgramValidation, SinePeakBeyondFourAmpsIsAmplitude) {
  proto::LoadSine m = sine_5Hz(1);
  m.offset_A = -2.0f;
  m.amplitude_A = 2.0f;  // reaches -4 A: allowed
  loaded(m);
  m.amplitude_A = 2.01f;
  EXPECT_EQ(refused_field(m), 1u);
}

TEST(ProgramValidation, MultisineLineSetErrorsAreLineLastAndPeakIsLineAmplitude) {
  proto::LoadMultisine m;
  m.line_first = 1;
  m.line_last = 400;
  m.line_step = 1;
  m.fundamental_Hz = 0.25f;  // 400 lines, up to 100 Hz
  m.line_amplitude_A = 0.0075f;
  loaded(m);
  m.line_last = 401;  // 401 lines
  EXPECT_EQ(refused_field(m), 3u);
  m.line_last = 401;
  m.line_step = 2;  // 201 lines again
  loaded(m);
  m.line_first = 10;
  m.line_last = 9;  // no line
  EXPECT_EQ(refused_field(m), 3u);
  // highest line: 125 Hz is the limit at both rates
  m.line_first = 1;
  m.line_last = 125;
  m.line_step = 1;
  m.fundamental_Hz = 1.0f;
  loaded(m);
  loaded(m, 40000);
  m.line_last = 126;
  EXPECT_EQ(refused_field(m), 3u);
  m.line_last = 100;
  m.line_amplitude_A = 0.04f;  // 1 A + 100 x 0.04 A could reach 5 A
  EXPECT_EQ(refused_field(m), 5u);
  m.line_amplitude_A = 0.01f;
  m.phase_mode = static_cast<proto::PhaseMode>(9);
  EXPECT_EQ(refused_field(m), 6u);
}

TEST(ProgramValidation, UnsupportedControlRateIsRefusedWithoutAField) {
  ProgramRunner r;
  std::uint8_t field = 0;
  EXPECT_EQ(r.load(proto::LoadHold{}, 10000, field), ErrorCode::out_of_range);
  EXPECT_EQ(field, 255u);
}

}  // namespace
}  // namespace palp::fw
