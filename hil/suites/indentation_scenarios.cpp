// SPDX-License-Identifier: Apache-2.0
// A short indentation (the SDK's indent(), the paper's quasi-static protocol) on the specimen the
// floating tip touches: its stiffness and depth are finite and consistent with the contact model
// the analysis chose, and agree with the same run on the reference device when one is
// configured. What the scenario proves is in README.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench.hpp"
#include "palp/indent.hpp"

namespace palp::hil {
namespace {

/// Short settings: 0.5 -> 1.5 A by 0.1 A, 50 ms a step, one repetition with unload (about
/// 1 s of ramp), every channel at up to 1 kHz (less where the device streams less). The float
/// settles for the default 1.2 s: after 0.5 s the coil still rings from its impact on the
/// specimen, and where in that ringing the ramp starts moved k and delta0 by up to 15 % between
/// the image and palp-sim (1.3 % with 1.2 s).
IndentationSettings short_indentation(const DeviceInfo& d) {
  IndentationSettings s;
  s.start_A = 0.5;
  s.stop_A = 1.5;
  s.step_A = 0.1;
  s.dwell_s = 0.05;
  s.repetitions = 1;
  s.unload = true;
  s.displacement_limit_m = 5e-3;
  s.stream_rate_Hz = stream_rate_at_most(d, 1000.0);
  s.zero_pressure_s = 0.2;
  return s;
}

/// indent() with the calibration put back afterwards (it zeroes the pressure offsets in RAM).
IndentationRun indent_and_restore(Probe& probe, const IndentationSettings& s) {
  const Calibration before = probe.calibration();
  struct Restore {
    Probe& p;
    const Calibration& c;
    ~Restore() {
      try {
        p.set_calibration(c);
      } catch (const Error& e) {
        ADD_FAILURE() << "could not put the calibration back: " << e.what();
      }
    }
  } restore{probe, before};
  return indent(probe, s);
}

struct Descriptors {
  double k_N_per_m = NAN, delta0_m = NAN;
  std::string model;
};

/// Where the run went: the floating coil's position, the contact point, the deepest sample.
std::string travel(const IndentationRun& run) {
  const std::vector<double>& z = run.recording.z_mm;
  char text[160];
  std::snprintf(
      text, sizeof text, "floated at %.3f mm, contact at %.3f mm, deepest %.3f mm",
      run.float_z_m * 1e3,
      run.analysis && run.analysis->contact_z_m ? *run.analysis->contact_z_m.value * 1e3 : NAN,
      z.empty() ? NAN : *std::max_element(z.begin(), z.end()));
  return text;
}

/// The chosen model's k (tangent at delta0) and delta0, after checking the run gave them.
Descriptors descriptors(const IndentationRun& run, const char* where) {
  Descriptors d;
  EXPECT_EQ(run.program.end, proto::ProgramEnd::completed) << where;
  EXPECT_EQ(run.samples_missing, 0u) << where;
  if (!run.analysis) {
    ADD_FAILURE() << where << ": no analysis: " << run.analysis_reason;
    return d;
  }
  const analysis::IndentationResult& a = *run.analysis;
  if (!a.chosen) {
    ADD_FAILURE() << where << ": no model fitted: " << a.fit_reason;
    return d;
  }
  d.model = analysis::model_name(*a.chosen);
  if (a.k_tangent_at_delta0_N_per_m)
    d.k_N_per_m = *a.k_tangent_at_delta0_N_per_m.value;
  else
    ADD_FAILURE() << where << ": no k: " << a.k_tangent_at_delta0_N_per_m.reason;
  if (a.delta0_m)
    d.delta0_m = *a.delta0_m.value;
  else
    ADD_FAILURE() << where << ": no delta0: " << a.delta0_m.reason;
  return d;
}

// The agreement of the image under QEMU with palp-sim placed like its plant (the scene:
// firmware/board/qemu/plant/README.md, whose float model agrees with hil/plant's to 1e-6). What
// separates two runs is the sensor noise of one short repetition: palp-sim's own k and delta0
// spread 0.46 % and 0.47 % (s.d., 12 runs), so two runs differ with an s.d. of 0.65 %; the
// image against palp-sim measured -1.3, 0.0, -1.1 % in k and +1.3, 0.0, +1.1 % in delta0.
// 5 % is 7.7 of those s.d. and leaves room for the image's own noise generator (triangular
// dither) and for QEMU's late ticks (caught up, but the plant then sees them bunched).
constexpr double kAgreeK = 0.05;       // relative
constexpr double kAgreeDelta0 = 0.05;  // relative

using Indentation = Scenario;
TEST_F(Indentation, AShortStaircaseGivesFiniteKAndDelta0ConsistentWithTheModelAndTheReference) {
  if (!Bench::get().has_specimen())
    GTEST_SKIP() << "the indentation needs a specimen that the floating tip (0.5 A) touches; "
                    "set PALP_BENCH_SPECIMEN=1 once one is placed";
  const IndentationSettings s = short_indentation(probe().info());
  ASSERT_GT(s.stream_rate_Hz, 0.0) << "no stream rate up to 1 kHz divides the control rate";
  const IndentationRun run = indent_and_restore(probe(), s);
  const Descriptors here = descriptors(run, "the device");
  ASSERT_FALSE(HasFailure());
  // finite and plausible: the depth lies inside the ramp's travel (the ramp turns round 5 mm
  // from where it started), and k delta0 / F0 is what the chosen model makes it: 1 for a line,
  // 3/2 for Hertz, 2 for Sneddon's cone (F = s delta^n gives k_t(delta0) delta0 = n F0)
  const double F0_N = run.analysis->F0_N;
  EXPECT_GT(here.delta0_m, 0.0);
  EXPECT_LT(here.delta0_m, s.displacement_limit_m);
  EXPECT_GT(here.k_N_per_m, 0.0);
  const double n = here.model == "linear" ? 1.0 : here.model == "hertz" ? 1.5 : 2.0;
  EXPECT_NEAR(here.k_N_per_m * here.delta0_m / F0_N, n, 0.05 * n) << here.model;
  std::printf("[  FIGURES ] %s: k %.1f N/m, delta0 %.3f mm (%s, F0 %.3f N, %.0f Hz); %s\n",
              probe().uri().c_str(), here.k_N_per_m, here.delta0_m * 1e3, here.model.c_str(), F0_N,
              s.stream_rate_Hz, travel(run).c_str());

  const std::string& ref_uri = Bench::get().reference_uri();
  if (ref_uri.empty()) return;  // no reference configured: nothing to compare with
  Probe ref(ref_uri);
  const IndentationRun ref_run = indent_and_restore(ref, s);
  const Descriptors there = descriptors(ref_run, "the reference");
  ASSERT_FALSE(HasFailure());
  std::printf(
      "[  FIGURES ] reference %s: k %.1f N/m, delta0 %.3f mm (%s); %s; device/reference "
      "k %+.1f %%, delta0 %+.1f %%\n",
      ref_uri.c_str(), there.k_N_per_m, there.delta0_m * 1e3, there.model.c_str(),
      travel(ref_run).c_str(), 100 * (here.k_N_per_m / there.k_N_per_m - 1),
      100 * (here.delta0_m / there.delta0_m - 1));
  EXPECT_NEAR(here.k_N_per_m, there.k_N_per_m, kAgreeK * there.k_N_per_m);
  EXPECT_NEAR(here.delta0_m, there.delta0_m, kAgreeDelta0 * there.delta0_m);
}

}  // namespace
}  // namespace palp::hil
