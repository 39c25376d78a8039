// SPDX-License-Identifier: Apache-2.0
// Elastic contact laws: Hertz, exact Sneddon sphere, the bottom effect, the series structural
// spring; values against closed forms and against analysis-notes' worked numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "palp/plant/contact.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;

TEST(Hertz, ForceAndTangentFollowTheClosedForm) {
  const ElasticPoint p = hertz_sphere(1e6, kR, 1e-3);
  EXPECT_NEAR(p.force_N, 4.0 / 3.0 * 1e6 * std::sqrt(kR) * std::pow(1e-3, 1.5), 1e-12);
  EXPECT_NEAR(p.stiffness_N_per_m, 2.0 * 1e6 * std::sqrt(kR * 1e-3), 1e-9);
  EXPECT_EQ(hertz_sphere(1e6, kR, -1e-3).force_N, 0.0);
}

// analysis-notes.md: F_Sneddon / F_Hertz at equal depth.
TEST(Sneddon, RatioToHertzMatchesWorkedValues) {
  const double ratio_at[][2] = {{0.04, 0.996}, {0.17, 0.983}, {0.42, 0.958},
                                {0.88, 0.912}, {1.33, 0.868}, {1.74, 0.828}};
  for (const auto& r : ratio_at) {
    const double d = r[0] * kR;
    const double ratio = sneddon_sphere(1e6, kR, d).force_N / hertz_sphere(1e6, kR, d).force_N;
    EXPECT_NEAR(ratio, r[1], 0.0015) << "delta/R = " << r[0];
  }
}

// analysis-notes.md: a = 2.03 / 2.18 / 2.39 mm at the paper's insert / solid / hollow depths.
TEST(Sneddon, ContactRadiusAtPaperOperatingDepthsStaysBelowR) {
  EXPECT_NEAR(sneddon_contact_radius(kR, 2.314e-3) * 1e3, 2.03, 0.006);
  EXPECT_NEAR(sneddon_contact_radius(kR, 2.935e-3) * 1e3, 2.18, 0.006);
  EXPECT_NEAR(sneddon_contact_radius(kR, 4.49e-3) * 1e3, 2.39, 0.006);
  EXPECT_LT(sneddon_contact_radius(kR, 20e-3), kR);
}

// The law's definition with the library's atanh throughout, solved by bisection: the contact
// radius u R with u atanh(u) = delta / R and F = E* R^2 ((1 + u^2) atanh(u) - u). The plant takes
// atanh from log above u = 0.1 for speed (contact_laws.cpp): it stays within roundoff of this.
TEST(Sneddon, AgreesWithTheLibraryAtanhFormToRoundoff) {
  for (double d = 1e-7; d < 20e-3; d *= 1.37) {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (mid * std::atanh(mid) < d / kR ? lo : hi) = mid;
    }
    const double u = 0.5 * (lo + hi);
    const double force = 1e6 * kR * kR * ((1.0 + u * u) * std::atanh(u) - u);
    EXPECT_NEAR(sneddon_contact_radius(kR, d) / kR, u, 1e-13 * u) << "delta = " << d;
    // 1e-11: Newton's stopping test (a step below 1e-13 u) grows by 1 / (1 - u) in the force
    // toward u = 1 (about 1e-12 at delta / R = 6), with the library's atanh as with the plant's
    if (u >= 1e-2) {  // below, both the plant and this cancel: the plant takes a series there
      EXPECT_NEAR(sneddon_sphere(1e6, kR, d).force_N, force, 1e-11 * force) << "delta = " << d;
    }
  }
}

TEST(Sneddon, TangentIsTwoEStarAAndMatchesTheDerivative) {
  for (double d : {1e-6, 1e-4, 1e-3, 3e-3, 6e-3}) {
    const ElasticPoint p = sneddon_sphere(2e5, kR, d);
    const double h = 1e-9 * std::max(d, 1e-4);
    const double num =
        (sneddon_sphere(2e5, kR, d + h).force_N - sneddon_sphere(2e5, kR, d - h).force_N) / (2 * h);
    EXPECT_NEAR(p.stiffness_N_per_m, num, 1e-5 * p.stiffness_N_per_m) << d;
    EXPECT_NEAR(p.stiffness_N_per_m, 2.0 * 2e5 * sneddon_contact_radius(kR, d), 1e-9);
  }
}

// The plant's Sneddon law comes from a table (sneddon_sphere_tabulated): against the exact law,
// solved by Newton, at 400 depths in each of the table's 512 cells and log-spaced down to
// 1e-10 R, force and stiffness agree to kSneddonTableError relative; beyond the table it is the
// exact law itself.
TEST(Sneddon, TabulatedLawIsTheExactLawWithinItsStatedErrorOverTheWholeTable) {
  double worst_force = 0.0, worst_stiffness = 0.0, worst_at = 0.0;
  auto compare = [&](double d) {
    const ElasticPoint exact = sneddon_sphere(1e6, kR, d * kR);
    const ElasticPoint table = sneddon_sphere_tabulated(1e6, kR, d * kR);
    const double ef = std::abs(table.force_N / exact.force_N - 1.0);
    const double ek = std::abs(table.stiffness_N_per_m / exact.stiffness_N_per_m - 1.0);
    if (std::max(ef, ek) > std::max(worst_force, worst_stiffness)) worst_at = d;
    worst_force = std::max(worst_force, ef);
    worst_stiffness = std::max(worst_stiffness, ek);
  };
  const int n = 512 * 400;
  for (int k = 1; k < n; ++k) compare(kSneddonTableMaxDepth * (k + 0.37) / n);
  for (double d = 1e-10; d < 0.01; d *= 1.01) compare(d);
  std::printf("Sneddon table: max relative error %.2e (force), %.2e (stiffness), worst at "
              "depth / R = %.4f\n", worst_force, worst_stiffness, worst_at);
  EXPECT_LT(worst_force, kSneddonTableError);
  EXPECT_LT(worst_stiffness, kSneddonTableError);
  for (const double d : {kSneddonTableMaxDepth, 5.0, 8.0}) {
    EXPECT_EQ(sneddon_sphere_tabulated(1e6, kR, d * kR).force_N, sneddon_sphere(1e6, kR, d * kR).force_N);
  }
  EXPECT_EQ(sneddon_sphere_tabulated(1e6, kR, 0.0).force_N, 0.0);
  EXPECT_EQ(sneddon_sphere_tabulated(1e6, kR, -1e-3).stiffness_N_per_m, 0.0);
}

TEST(Sneddon, ShallowLimitIsHertz) {
  const double d = 1e-8;
  EXPECT_NEAR(sneddon_sphere(1e6, kR, d).force_N / hertz_sphere(1e6, kR, d).force_N, 1.0, 1e-6);
}

TEST(Sneddon, WarmStartGivesTheColdAnswer) {
  double hint = 0.3;  // far from the answer
  const double warm = sneddon_sphere(1e6, kR, 4e-3, &hint).force_N;
  EXPECT_NEAR(warm, sneddon_sphere(1e6, kR, 4e-3).force_N, 1e-12);
  EXPECT_NEAR(hint, sneddon_contact_radius(kR, 4e-3) / kR, 1e-12);
}

TEST(BottomEffect, FactorAndItsTangentAreConsistent) {
  EXPECT_DOUBLE_EQ(bottom_effect_factor(0.0), 1.0);
  EXPECT_NEAR(bottom_effect_factor(0.5),
              1 + 1.133 * 0.5 + 1.283 * 0.25 + 0.769 * 0.125 + 0.0975 * 0.0625, 1e-12);
  ContactParams p;
  p.law = ContactLaw::sneddon;
  p.e_star_Pa = 1.2e5;
  p.layer_thickness_m = 7e-3;
  for (double d : {0.5e-3, 2e-3, 5e-3}) {
    const double h = 1e-9;
    const double num =
        (sphere_on_layer(p, kR, d + h).force_N - sphere_on_layer(p, kR, d - h).force_N) / (2 * h);
    EXPECT_NEAR(sphere_on_layer(p, kR, d).stiffness_N_per_m, num, 1e-5 * num);
  }
  // A thin layer is stiffer than the half-space.
  ContactParams half = p;
  half.layer_thickness_m = 0.0;
  EXPECT_GT(sphere_on_layer(p, kR, 2e-3).force_N, 1.3 * sphere_on_layer(half, kR, 2e-3).force_N);
}

TEST(SeriesSpring, DepthSplitsIntoContactAndStructureAndTangentsAddAsCompliances) {
  ContactParams p;
  p.law = ContactLaw::sneddon;
  p.e_star_Pa = 1e6;
  p.structural_compliance_m_per_N = 2.5e-3;
  for (double d : {0.2e-3, 1e-3, 4e-3}) {
    double dc = 0.0;
    const ElasticPoint s = elastic_contact(p, kR, d, &dc);
    const ElasticPoint c = sphere_on_layer(p, kR, dc);
    EXPECT_NEAR(dc + p.structural_compliance_m_per_N * s.force_N, d, 1e-12);
    EXPECT_NEAR(s.force_N, c.force_N, 1e-12);
    EXPECT_NEAR(1.0 / s.stiffness_N_per_m,
                1.0 / c.stiffness_N_per_m + p.structural_compliance_m_per_N, 1e-9);
  }
}

TEST(SeriesSpring, WarmStartFromAnywhereConverges) {
  ContactParams p;
  p.law = ContactLaw::hertz;
  p.e_star_Pa = 3.3e6;
  p.structural_compliance_m_per_N = 2.5e-4;
  double cold_hint = 0.0;
  const double f = elastic_contact(p, kR, 3e-3, &cold_hint).force_N;
  for (double start : {1e-9, 1e-3, 2.9e-3, 3e-3}) {
    double hint = start;
    EXPECT_NEAR(elastic_contact(p, kR, 3e-3, &hint).force_N, f, 1e-12) << start;
  }
}

}  // namespace
}  // namespace palp::plant
