// SPDX-License-Identifier: Apache-2.0
// palp::indent against palp-sim linked in (palp/sim_inproc.hpp: virtual time as fast as the SDK reads): the 1D acceptance of issue 6 at
// position 3 of the paper's three objects, the recording it returns, the displacement limit,
// and the errors that come before the device does anything.
//
// The probe is mounted as the paper's protocol has it: at position 3 (x = 27 mm), the mount
// 25 mm above the flat top, so the coil floating at I_c = 0.5 A (25 mm of stroke) just touches
// and the ramp starts in contact. The 1D preset runs 5 repetitions; the acceptance runs 2 (the
// per-repetition s.d. needs two; device time 25-45 s per object instead of 60-120 s; 1 on the
// insert, see there) and streams at
// 200 Hz instead of 1 kHz: 20 samples per step are plenty for the fits (the rate was chosen
// when the fits ran on every sample; they now run on the steps' plateau means, issue 16).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "palp/indent.hpp"
#include "palp/probe.hpp"
#include "palp/sim_inproc.hpp"
#include "sim_process.hpp"

namespace {

using palp::IndentationPreset;
using palp::IndentationRun;
using palp::IndentationSettings;
using palp::sim::InprocSimulator;
using palp::sim::test::SimProcess;
using testing::HasSubstr;
using namespace std::chrono_literals;

struct Paper {
  const char* phantom;
  double delta0_mm, k_o_N_per_mm;
};
// paper §IV-A, position 3
constexpr Paper kInsert{"insert_1d", 2.314, 0.94571};
constexpr Paper kSolid{"solid_1d", 2.935, 0.74555};
constexpr Paper kHollow{"hollow_1d", 4.49, 0.3249};

IndentationRun indent_at_position_3(const char* phantom, int reps, double* wall_s = nullptr) {
  InprocSimulator sim({.phantom = phantom, .mount_mm = {27, 0, -25}});
  palp::Probe probe(sim.transport());
  IndentationSettings s = IndentationSettings::preset(IndentationPreset::one_d);
  s.repetitions = reps;
  s.stream_rate_Hz = 200;  // 20 samples per 100 ms step
  const auto t0 = std::chrono::steady_clock::now();
  IndentationRun run = palp::indent(probe, s);
  if (wall_s) *wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

double delta0_mm(const IndentationRun& r) { return *r.analysis->delta0_m.value * 1e3; }
double k_o(const IndentationRun& r) { return *r.analysis->k_tangent_at_delta0_N_per_m.value * 1e-3; }

void expect_paper(const IndentationRun& r, const Paper& p) {
  ASSERT_TRUE(r.analysis) << r.analysis_reason;
  ASSERT_TRUE(r.analysis->delta0_m) << r.analysis->delta0_m.reason;
  ASSERT_TRUE(r.analysis->k_tangent_at_delta0_N_per_m);
  EXPECT_NEAR(delta0_mm(r), p.delta0_mm, 0.10 * p.delta0_mm) << p.phantom;
  EXPECT_NEAR(k_o(r), p.k_o_N_per_mm, 0.10 * p.k_o_N_per_mm) << p.phantom;
}

void report(const IndentationRun& r, const char* phantom, double wall_s) {
  std::printf("%-10s model %-8s delta0 %.3f mm  k_o %.4f N/mm  k_fd %.4f N/mm  %zu samples, "
              "%.1f s device, %.2f s wall\n",
              phantom, r.analysis->chosen ? palp::analysis::model_name(*r.analysis->chosen) : "none",
              r.analysis->delta0_m ? delta0_mm(r) : -1.0,
              r.analysis->k_tangent_at_delta0_N_per_m ? k_o(r) : -1.0,
              r.analysis->k_fd_N_per_m ? *r.analysis->k_fd_N_per_m.value * 1e-3 : -1.0,
              r.recording.size(), r.recording.t_s.back() - r.recording.t_s.front(), wall_s);
}

// The ordering insert > solid > hollow follows from each object's k_o lying within 10 % of the
// paper's: those bands are disjoint and ordered (one test per object, so they run in parallel).
static_assert(0.9 * kInsert.k_o_N_per_mm > 1.1 * kSolid.k_o_N_per_mm);
static_assert(0.9 * kSolid.k_o_N_per_mm > 1.1 * kHollow.k_o_N_per_mm);

TEST(Indent, HollowPosition3IsLinearByAicWithDelta0AndKoWithinTenPercentOfThePaper) {
  double wall = 0;
  const IndentationRun r = indent_at_position_3(kHollow.phantom, 2, &wall);
  ASSERT_TRUE(r.analysis) << r.analysis_reason;
  report(r, kHollow.phantom, wall);
  expect_paper(r, kHollow);
  ASSERT_TRUE(r.analysis->chosen);
  EXPECT_EQ(*r.analysis->chosen, palp::analysis::Model::linear);  // structural compliance
  // the ramp turned round at the 5 mm displacement limit, well below 3 A
  EXPECT_EQ(r.program.end, palp::proto::ProgramEnd::completed);
  double top_A = 0, top_z = -1e9, first_z = r.recording.z_mm.front();
  for (std::size_t k = 0; k < r.recording.size(); ++k) {
    top_A = std::max(top_A, (*r.recording.i_cmd_A)[k]);
    top_z = std::max(top_z, r.recording.z_mm[k]);
  }
  EXPECT_LT(top_A, 1.5);
  EXPECT_NEAR(top_z - first_z, 5.0, 0.3);
  ASSERT_TRUE(r.repetitions);
  EXPECT_EQ(r.repetitions->per_rep.size(), 2u);
  EXPECT_EQ(r.recording.rep.back(), 1);
}

TEST(Indent, SolidPosition3IsHertzOrSneddonByAicWithDelta0AndKoWithinTenPercentOfThePaper) {
  double wall = 0;
  const IndentationRun r = indent_at_position_3(kSolid.phantom, 2, &wall);
  ASSERT_TRUE(r.analysis) << r.analysis_reason;
  report(r, kSolid.phantom, wall);
  expect_paper(r, kSolid);
  ASSERT_TRUE(r.analysis->chosen);
  EXPECT_NE(*r.analysis->chosen, palp::analysis::Model::linear);
  // the recording: the ramp's samples only, pressures zeroed first, at the asked rate
  EXPECT_DOUBLE_EQ((*r.recording.i_cmd_A).front(), 0.5);
  EXPECT_NEAR(r.recording.t_s[1] - r.recording.t_s[0], 1.0 / 200, 1e-9);
  EXPECT_EQ(r.samples_missing, 0u);
  ASSERT_TRUE(r.recording.sidecar);
  EXPECT_EQ(r.recording.sidecar->zeroing.at(0)["what"], "pressure_zero");
  EXPECT_EQ(r.recording.sidecar->program["parameters"]["displacement_limit_mm"], 5.0);
  EXPECT_NEAR(r.float_z_m, 25e-3, 0.2e-3);  // the floating coil rested at the surface
}

TEST(Indent, InsertPosition3HasDelta0AndKoWithinTenPercentOfThePaper) {
  double wall = 0;
  // one repetition: the Sneddon fit of the insert's bent curve is the slow part of the analysis
  // (~4 s per repetition here), and the descriptors' s.d. is shown on the other two objects
  const IndentationRun r = indent_at_position_3(kInsert.phantom, 1, &wall);
  ASSERT_TRUE(r.analysis) << r.analysis_reason;
  report(r, kInsert.phantom, wall);
  expect_paper(r, kInsert);
}

TEST(Indent, ACoilLeftFloatingByAContactWatchIsReleasedThenZeroedAndFloatedAgain) {
  // the toucher leaves the coil holding 0.5 A on the surface; the 2D preset (25 ms steps) follows
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  palp::Probe probe(sim.transport());
  palp::ContactWatchProgram w;
  w.hold_current_A = 0.5f;
  w.threshold_counts = 500;
  probe.load(w);
  probe.start();
  ASSERT_TRUE(probe.wait_contact(10s));
  ASSERT_NEAR(probe.status().i_cmd_A, 0.5, 1e-3);  // the watch ended holding its current

  IndentationSettings s = IndentationSettings::preset(IndentationPreset::two_d);
  s.repetitions = 1;
  s.stream_rate_Hz = 500;
  std::vector<std::string> phases;
  const IndentationRun r = palp::indent(probe, s, [&](const palp::IndentProgress& p) {
    if (phases.empty() || phases.back() != p.phase) phases.push_back(p.phase);
  });
  EXPECT_THAT(phases, testing::ElementsAre("releasing the coil", "zeroing pressures",
                                           "floating the coil", "ramp"));
  EXPECT_NEAR(r.float_z_m, 25e-3, 0.2e-3);
  ASSERT_TRUE(r.analysis) << r.analysis_reason;
  ASSERT_TRUE(r.analysis->delta0_m);
  EXPECT_NEAR(*r.analysis->delta0_m.value * 1e3, kSolid.delta0_mm, 0.1 * kSolid.delta0_mm);
  EXPECT_NEAR(r.recording.t_s[1] - r.recording.t_s[0], 2e-3, 1e-9);
  EXPECT_NEAR(probe.status().i_cmd_A, 0.0, 1e-6);  // and the coil is left at 0 A
}

TEST(Indent, CancelledMidRampStopsTheRampKeepsWhatWasRecordedAndLeavesZeroCurrent) {
  // palp-sim paced at 20x, not in process: progress (which cancels) is reported every 200 ms
  // of wall time, over 50 s of the ramp unpaced (at over 200x); the in-process simulator cannot
  // be paced
  SimProcess sim({"--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"}, false);
  ASSERT_TRUE(sim.ok());
  ASSERT_EQ(sim.control("pace 20"), "ok");
  palp::Probe probe(sim.uri());
  IndentationSettings s = IndentationSettings::preset(IndentationPreset::one_d);
  s.stream_rate_Hz = 200;
  double fraction = 0;
  const IndentationRun r = palp::indent(
      probe, s, [&](const palp::IndentProgress& p) { fraction = p.fraction; },
      [&] { return fraction > 0.02; });  // about 5 s of the 250 s ramp
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.program.end, palp::proto::ProgramEnd::stopped_by_host);
  ASSERT_GT(r.recording.size(), 0u);
  EXPECT_LT(r.recording.t_s.back() - r.recording.t_s.front(), 0.2 * s.ramp_duration_s());
  ASSERT_TRUE(r.recording.sidecar);
  EXPECT_EQ(r.recording.sidecar->extra["interrupted"], true);
  EXPECT_NEAR(probe.status().i_cmd_A, 0.0, 1e-6);
}

TEST(Indent, BadSettingsAreRefusedBeforeTheDeviceMoves) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  IndentationSettings s = IndentationSettings::preset(IndentationPreset::two_d);
  s.stream_rate_Hz = 5000;
  try {
    palp::indent(probe, s);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "indentation settings: stream_rate_Hz must lie in (0, 1000] Hz");
  }
  EXPECT_TRUE(probe.zeroing().empty());  // nothing was zeroed
  EXPECT_EQ(probe.status().program, palp::proto::ProgramKind::none);
}

}  // namespace
