// SPDX-License-Identifier: Apache-2.0
// The 16 s contact multisine (IdentificationPreset::contact_multisine_fast, issue 24) against
// the plant's own small-signal linearisation (palp/plant/linearisation.hpp) on palp-sim linked in
// (virtual time): omega_n within 0.5 % and zeta within 5 % on the three 1D objects at position 3
// and at the pad's operating point (1.0 A, the floating tip just touching), as the 60 s
// contact_multisine at its small-signal 0.03 A (test_identification.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "palp/identification.hpp"
#include "palp/plant/linearisation.hpp"
#include "palp/probe.hpp"
#include "palp/sim_inproc.hpp"
#include "sanitized.hpp"

namespace identification_fast {  // named: the sim tests build as one unity file
namespace {

using palp::IdentificationPreset;
using palp::IdentificationSettings;
using palp::sim::test::kSanitized;

constexpr std::uint32_t kControlRate_Hz = 20000;

/// A probing site: the phantom, the apex's (x, y), mm.
struct Site {
  const char* phantom;
  double x_mm, y_mm;
};
constexpr Site kInsert{"insert_1d", 27, 0}, kSolid{"solid_1d", 27, 0}, kHollow{"hollow_1d", 27, 0};
// the pad's row 5: column 4 (bulk) and column 5 (over shallow channel 5, the softest site)
constexpr Site kPadBulk{"pad_2d", 40, 45}, kPadChannel{"pad_2d", 50, 45};
// the same site in pad_2d_damping's inclusion (twice the retardation time, the same stiffness)
constexpr Site kPadInclusion{"pad_2d_damping", 40, 45};

/// The plant as palp-sim builds it with the mount where the floating tip (25 mm of stroke) just
/// touches the site (the sphere's first touch), linearised at bias_A; mount_z_mm gets that z.
palp::plant::Linearisation reference(const Site& site, double bias_A, double* mount_z_mm) {
  palp::plant::Plant plant(palp::plant::PlantConfig{},
                           palp::plant::load_shipped_phantom(site.phantom));
  plant.set_mount(site.x_mm * 1e-3, site.y_mm * 1e-3, -0.05);
  const double z_m = plant.site_touch().apex_z_m - 0.025;
  plant.set_mount(site.x_mm * 1e-3, site.y_mm * 1e-3, z_m);
  if (mount_z_mm) *mount_z_mm = z_m * 1e3;
  return palp::plant::linearise(plant, bias_A);
}

struct Errors {
  double omega_n = 1, zeta = 1;  // relative
  double omega_n_rad_per_s = 0, zeta_measured = 0;
};

/// Identifies `site` with the fast preset and compares with the linearisation; prints the figures.
Errors fast_errors(const Site& site) {
  const IdentificationSettings s =
      IdentificationSettings::preset(IdentificationPreset::contact_multisine_fast);
  double z_mm = 0;
  const auto ref = reference(site, s.bias_A, &z_mm);
  palp::sim::InprocSimulator sim(
      {.phantom = site.phantom, .mount_mm = {site.x_mm, site.y_mm, z_mm}});
  palp::Probe probe(sim.transport());
  const palp::IdentificationRun r = palp::identify(probe, s);
  EXPECT_TRUE(r.fit) << r.analysis_reason;
  if (!r.fit || !r.frf) return {};
  const Errors e{r.fit->omega_n_rad_per_s / ref.omega_n_rad_per_s - 1, r.fit->zeta / ref.zeta - 1,
                 r.fit->omega_n_rad_per_s, r.fit->zeta};
  std::printf("%-9s (%2.0f, %2.0f) mm: omega_n %.3f rad/s (ref %.3f, %+.3f %%), zeta %.4f (ref "
              "%.4f, %+.2f %%, s.e. %.2f %%), cost %.2f, %zu lines, %.0f s device\n",
              site.phantom, site.x_mm, site.y_mm, r.fit->omega_n_rad_per_s, ref.omega_n_rad_per_s,
              100 * e.omega_n, r.fit->zeta, ref.zeta, 100 * e.zeta,
              100 * r.fit->zeta_se / r.fit->zeta,
              r.fit->normalized_cost.value_or(-1), r.fit->lines, r.frf->device_time_s);
  EXPECT_TRUE(r.fit->adequate) << site.phantom;
  EXPECT_EQ(r.frf->device_time_s, 16.0);
  return e;
}

TEST(IdentificationFast, PresetIsSixteenSecondsOfSeventySixOddLinesWithSchroederPhasesAt30mA) {
  const IdentificationSettings s =
      IdentificationSettings::preset(IdentificationPreset::contact_multisine_fast);
  s.validate();
  EXPECT_NO_THROW(s.check_excitation(kControlRate_Hz));  // 1.0 A - 0.03 A stays above I_c
  EXPECT_DOUBLE_EQ(s.device_time_s(kControlRate_Hz), 16.0);  // 4 periods of 4 s
  const palp::proto::LoadMultisine m = s.multisine_program(kControlRate_Hz);
  EXPECT_EQ(m.line_first, 9);    // 2.25 Hz
  EXPECT_EQ(m.line_last, 159);   // 39.75 Hz
  EXPECT_EQ(m.line_step, 2);     // odd harmonics: the even ones stay empty
  EXPECT_EQ(m.periods, 4);
  EXPECT_EQ(m.phase_mode, palp::proto::PhaseMode::schroeder);
  EXPECT_NEAR(s.peak_A(kControlRate_Hz), 0.03, 1e-6);
  // Schroeder's crest factor over 76 lines: peak / (rms = line sqrt(76 / 2)) below 2
  const double crest = s.peak_A(kControlRate_Hz) / (m.line_amplitude_A * std::sqrt(38.0));
  std::printf("line amplitude %.3f mA, crest factor %.2f\n", 1e3 * m.line_amplitude_A, crest);
  EXPECT_LT(crest, 2.0);
}

TEST(IdentificationFast, BandSpansAThirdOfTheSoftestToOnePointFiveTimesTheStiffestResonance) {
  const IdentificationSettings s =
      IdentificationSettings::preset(IdentificationPreset::contact_multisine_fast);
  const palp::proto::LoadMultisine m = s.multisine_program(kControlRate_Hz);
  const double f_first = m.line_first * s.fundamental_Hz, f_last = m.line_last * s.fundamental_Hz;
  for (const Site& site : {kInsert, kSolid, kHollow, kPadBulk, kPadChannel}) {
    const double f_n =
        reference(site, s.bias_A, nullptr).omega_n_rad_per_s / (2 * std::numbers::pi);
    std::printf("%-9s (%2.0f, %2.0f) mm: f_n %.2f Hz\n", site.phantom, site.x_mm, site.y_mm, f_n);
    EXPECT_LT(f_first, f_n / 2.9) << site.phantom;
    EXPECT_GT(f_last, 1.5 * f_n) << site.phantom;
  }
}

TEST(IdentificationFast, OneDObjectsAtPosition3MatchTheLinearisation) {
  if (kSanitized) GTEST_SKIP() << "three 16 s multisines: the release build runs them";
  for (const Site& site : {kInsert, kSolid, kHollow}) {
    const Errors e = fast_errors(site);
    EXPECT_LT(std::fabs(e.omega_n), 0.005) << site.phantom;
    EXPECT_LT(std::fabs(e.zeta), 0.05) << site.phantom;
  }
}

TEST(IdentificationFast, PadAtItsOperatingPointMatchesTheLinearisationOverBulkAndChannel) {
  if (kSanitized) GTEST_SKIP() << "two 16 s multisines: the release build runs them";
  for (const Site& site : {kPadBulk, kPadChannel}) {
    const Errors e = fast_errors(site);
    EXPECT_LT(std::fabs(e.omega_n), 0.005) << site.phantom << " x " << site.x_mm;
    EXPECT_LT(std::fabs(e.zeta), 0.05) << site.phantom << " x " << site.x_mm;
  }
}

TEST(IdentificationFast, DampingInclusionShowsInZetaAndNotInOmegaN) {
  if (kSanitized) GTEST_SKIP() << "two 16 s multisines: the release build runs them";
  const Errors pad = fast_errors(kPadBulk), inclusion = fast_errors(kPadInclusion);
  EXPECT_LT(std::fabs(inclusion.omega_n), 0.005);
  EXPECT_LT(std::fabs(inclusion.zeta), 0.05);
  // the linearisation's ratio is 1.81 (tests/plant/test_pad_viscoelastic.cpp)
  EXPECT_GT(inclusion.zeta_measured / pad.zeta_measured, 1.7);
  EXPECT_NEAR(inclusion.omega_n_rad_per_s, pad.omega_n_rad_per_s, 0.005 * pad.omega_n_rad_per_s);
}

TEST(IdentificationFast, RunReanalysedFromItsSidecarGivesTheSameFitWithSchroederPhases) {
  if (kSanitized) GTEST_SKIP() << "a 16 s multisine: the release build runs it";
  const IdentificationSettings s =
      IdentificationSettings::preset(IdentificationPreset::contact_multisine_fast);
  double z_mm = 0;
  (void)reference(kPadChannel, s.bias_A, &z_mm);
  palp::sim::InprocSimulator sim(
      {.phantom = kPadChannel.phantom, .mount_mm = {kPadChannel.x_mm, kPadChannel.y_mm, z_mm}});
  palp::Probe probe(sim.transport());
  const palp::IdentificationRun r = palp::identify(probe, s);
  ASSERT_TRUE(r.fit) << r.analysis_reason;
  palp::IdentificationRun again = palp::identification_run_of(r.recording);
  EXPECT_EQ(again.settings.phase_mode, palp::proto::PhaseMode::schroeder);
  EXPECT_EQ(again.multisine, r.multisine);
  palp::analyze_identification(again);
  ASSERT_TRUE(again.fit) << again.analysis_reason;
  EXPECT_DOUBLE_EQ(again.fit->omega_n_rad_per_s, r.fit->omega_n_rad_per_s);
  EXPECT_DOUBLE_EQ(again.fit->zeta, r.fit->zeta);
}

}  // namespace
}  // namespace identification_fast
