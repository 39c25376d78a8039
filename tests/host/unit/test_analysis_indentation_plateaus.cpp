// SPDX-License-Identifier: Apache-2.0
// The indentation fits on the staircase's plateau means (IndentationParams::fit_on, issue 16)
// against the fits on every sample: the same answer within the standard errors on a staircase
// whose probe rings inside each step as palp-sim's does, exactly the same answer when the probe
// rests on each level, and the samples whenever the commanded current is unknown.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "palp/analysis/indentation.hpp"
#include "test_analysis_synth.hpp"

using namespace palp::analysis;
using palp::analysis::test::SynthSpec;
using palp::analysis::test::synth_curve;

namespace {

constexpr double kPlateauTipR = 2.5e-3;
const double kPlateauSolidEstar = 745.55 / (2.0 * std::sqrt(kPlateauTipR * 2.935e-3));  // the paper's solid

// The 2D protocol's staircase as the device records it: 0.01 A steps held 25 ms at 1 kHz
// (25 samples a plateau), 2 mA rms current noise, 1 um encoder, the commanded current recorded.
SynthSpec ringing_staircase(double natural_Hz) {
  SynthSpec s;
  s.object_force = [](double d) { return hertz_force_N(d, kPlateauSolidEstar, kPlateauTipR); };
  s.i_top_A = 1.5;
  s.i_step_A = 0.01;
  s.samples_per_level = 25;
  s.reps = 3;
  s.noise_A = 0.002;
  s.quantum_m = 1e-6;
  s.command_column = true;
  s.natural_Hz = natural_Hz;
  return s;
}

IndentationResult analyse_fitting_on(const Curve& c, FitOn on) {
  IndentationParams p;
  p.fit_on = on;
  return analyze_indentation(c, p);
}

void print_fit_values(const char* path, const ModelFit& f) {
  std::printf("  %-8s %-8s", path, model_name(f.model));
  for (Eigen::Index j = 0; j < f.params.size(); ++j)
    std::printf("  %s %.7g (SE %.3g)", f.names[static_cast<std::size_t>(j)].c_str(), f.params[j], f.se[j]);
  std::printf("  points %d of %d samples\n", f.n_points, f.n);
}

}  // namespace

TEST(AnalysisIndentationPlateaus, PlateauAndSampleFitsAgreeWithinTheirStandardErrorsOnARingingStaircase) {
  // the coil rings at 10 Hz (zeta 0.25) inside every 25 ms step: z is far from constant on a
  // plateau, so the plateau means are not the samples
  const Curve c = synth_curve(ringing_staircase(10.0));
  const IndentationResult on_plateaus = analyse_fitting_on(c, FitOn::plateaus);
  const IndentationResult on_samples = analyse_fitting_on(c, FitOn::samples);
  EXPECT_EQ(on_plateaus.fitted_on, FitOn::plateaus);
  EXPECT_EQ(on_samples.fitted_on, FitOn::samples);
  // 100 steps up from 0.5 A, 3 repetitions: 303 plateaus, of which those where the probe
  // travels far (the rings' first cycles) enter as their samples; still a tenth of the samples
  EXPECT_GE(on_plateaus.n_fit_points, 3 * 101);
  EXPECT_LT(on_plateaus.n_fit_points, on_samples.n_loading / 10);
  EXPECT_EQ(on_samples.n_fit_points, on_samples.n_loading);
  ASSERT_TRUE(on_plateaus.chosen && on_samples.chosen);
  EXPECT_EQ(*on_plateaus.chosen, *on_samples.chosen);
  for (auto fit : {&IndentationResult::linear, &IndentationResult::hertz, &IndentationResult::sneddon}) {
    const auto& a = on_plateaus.*fit;
    const auto& b = on_samples.*fit;
    ASSERT_TRUE(a && b);
    print_fit_values("plateaus", *a);
    print_fit_values("samples", *b);
    EXPECT_EQ(a->n, b->n);
    for (Eigen::Index j = 0; j < a->params.size(); ++j) {
      EXPECT_LT(std::abs(a->params[j] - b->params[j]), std::max(a->se[j], b->se[j]))
          << model_name(a->model) << " " << a->names[static_cast<std::size_t>(j)];
      EXPECT_NEAR(a->se[j] / b->se[j], 1.0, 0.2) << model_name(a->model) << " " << a->names[static_cast<std::size_t>(j)];
    }
    EXPECT_NEAR(a->rss / b->rss, 1.0, 0.05) << model_name(a->model);
  }
  ASSERT_TRUE(on_plateaus.delta0_m && on_samples.delta0_m);
  std::printf("  delta0 %.5f / %.5f mm, k_o %.5f / %.5f N/mm (plateaus / samples)\n",
              *on_plateaus.delta0_m.value * 1e3, *on_samples.delta0_m.value * 1e3,
              *on_plateaus.k_tangent_at_delta0_N_per_m.value * 1e-3,
              *on_samples.k_tangent_at_delta0_N_per_m.value * 1e-3);
  EXPECT_NEAR(*on_plateaus.delta0_m.value / *on_samples.delta0_m.value, 1.0, 1e-3);
  EXPECT_NEAR(*on_plateaus.k_tangent_at_delta0_N_per_m.value / *on_samples.k_tangent_at_delta0_N_per_m.value,
              1.0, 1e-3);
  // the model-free descriptors do not depend on the fit points beyond the contact point
  ASSERT_TRUE(on_plateaus.k_window_N_per_m && on_samples.k_window_N_per_m);
  EXPECT_NEAR(*on_plateaus.k_window_N_per_m.value / *on_samples.k_window_N_per_m.value, 1.0, 1e-3);
}

TEST(AnalysisIndentationPlateaus, OnFlatPlateausTheFitIsTheSampleFit) {
  // the probe rests at each level's position: every sample of a plateau has the plateau's z,
  // so the plateau fit minimises the very same cost
  const Curve c = synth_curve(ringing_staircase(0.0));
  const IndentationResult a = analyse_fitting_on(c, FitOn::plateaus);
  const IndentationResult b = analyse_fitting_on(c, FitOn::samples);
  for (auto fit : {&IndentationResult::linear, &IndentationResult::hertz, &IndentationResult::sneddon}) {
    ASSERT_TRUE((a.*fit) && (b.*fit));
    const ModelFit& x = *(a.*fit);
    const ModelFit& y = *(b.*fit);
    for (Eigen::Index j = 0; j < x.params.size(); ++j) {
      EXPECT_NEAR(x.params[j], y.params[j], 1e-6 * y.se[j]) << model_name(x.model) << " " << j;
      EXPECT_NEAR(x.se[j], y.se[j], 1e-6 * y.se[j]) << model_name(x.model) << " " << j;
    }
    EXPECT_NEAR(x.rss, y.rss, 1e-9 * y.rss);
    EXPECT_NEAR(x.aic, y.aic, 1e-6);
    EXPECT_NEAR(x.r2, y.r2, 1e-12);
  }
  // and it still recovers the paper's solid
  ASSERT_TRUE(a.delta0_m && a.k_tangent_at_delta0_N_per_m);
  EXPECT_NEAR(*a.delta0_m.value, 2.935e-3, 0.005 * 2.935e-3);
  EXPECT_NEAR(*a.k_tangent_at_delta0_N_per_m.value, 745.55, 0.005 * 745.55);
}

TEST(AnalysisIndentationPlateaus, WithoutTheCommandedCurrentTheFitsRunOnTheSamples) {
  SynthSpec s = ringing_staircase(0.0);
  s.command_column = false;
  const Curve c = synth_curve(s);
  const IndentationResult r = analyse_fitting_on(c, FitOn::plateaus);
  EXPECT_EQ(r.fitted_on, FitOn::samples);
  EXPECT_EQ(r.n_fit_points, r.n_loading);
  ASSERT_TRUE(r.hertz);
  EXPECT_EQ(r.hertz->n_points, r.hertz->n);
}

TEST(AnalysisIndentationPlateaus, EachRepetitionIsFittedOnItsOwnPlateaus) {
  const RepetitionSummary s = analyze_repetitions(synth_curve(ringing_staircase(10.0)));
  ASSERT_EQ(s.per_rep.size(), 3u);
  for (const IndentationResult& r : s.per_rep) {
    EXPECT_EQ(r.fitted_on, FitOn::plateaus);
    EXPECT_GE(r.n_fit_points, 101);
    EXPECT_LT(r.n_fit_points, r.n_loading / 10);
  }
  EXPECT_EQ(s.delta0_m.n, 3);
}
