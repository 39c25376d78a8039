// SPDX-License-Identifier: Apache-2.0
// derived_se: the delta-method standard errors of delta0 and the tangent stiffnesses, on fits
// built by hand where the answer is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "palp/analysis/indentation.hpp"

using namespace palp::analysis;

namespace {

constexpr double kF0 = 1.459;  // N, K_f (I_0 - I_c) at the paper's defaults

/// A result whose chosen model is `fit`, with delta0 and the tangents the fit gives.
IndentationResult result_of(const ModelFit& fit, double delta0_m) {
  IndentationResult r;
  (fit.model == Model::linear ? r.linear : r.hertz) = fit;
  r.chosen = fit.model;
  r.F0_N = kF0;
  r.delta0_m = Value::of(delta0_m);
  r.k_tangent_at_delta0_N_per_m = Value::of(fit.stiffness_N_per_m(delta0_m));
  r.tangent_depths_m = {1e-3, 2e-3};
  r.k_tangent_N_per_m = {Value::of(fit.stiffness_N_per_m(1e-3)),
                         Value::absent("depth 2 mm, beyond the deepest sample")};
  return r;
}

ModelFit hertz_fit(double Estar_Pa, double se_Pa) {
  ModelFit f;
  f.model = Model::hertz;
  f.names = {"Estar_Pa", "contact_z_m"};
  f.params = Eigen::Vector2d(Estar_Pa, 0.01);
  f.se = Eigen::Vector2d(se_Pa, 1e-6);
  f.radius_m = 2.5e-3;
  return f;
}

}  // namespace

TEST(AnalysisIndentationSe, HertzGivesTwoThirdsOfTheRelativeErrorOnDelta0AndItsTangent) {
  // E* = 2 MPa +- 2 %, R = 2.5 mm, F_0 = 1.459 N: delta0 = (3 F_0 / (4 E* sqrt R))^(2/3)
  // = 0.49288 mm ~ E*^(-2/3), k_t(delta0) = 2 E* sqrt(R delta0) = 4440.2 N/m ~ E*^(2/3),
  // k_t(1 mm) = 6324.6 N/m ~ E*: se = 2/3 x 2 % x delta0, 2/3 x 2 % x k_t, 2 % x k_t(1 mm)
  const ModelFit fit = hertz_fit(2.0e6, 4.0e4);
  const DerivedSe se = derived_se(result_of(fit, 4.928836026392128e-4));
  ASSERT_TRUE(se.delta0_m);
  EXPECT_NEAR(*se.delta0_m.value, 6.571781368522837e-06, 1e-6 * 6.57e-6);
  ASSERT_TRUE(se.k_tangent_at_delta0_N_per_m);
  EXPECT_NEAR(*se.k_tangent_at_delta0_N_per_m.value, 59.20261871921022, 1e-6 * 59.2);
  ASSERT_EQ(se.k_tangent_N_per_m.size(), 2u);
  ASSERT_TRUE(se.k_tangent_N_per_m[0]);
  EXPECT_NEAR(*se.k_tangent_N_per_m[0].value, 126.49110640673518, 1e-9 * 126.5);
  EXPECT_FALSE(se.k_tangent_N_per_m[1]);
  EXPECT_EQ(se.k_tangent_N_per_m[1].reason, "depth 2 mm, beyond the deepest sample");
}

TEST(AnalysisIndentationSe, LinearGivesF0SeOverKSquaredOnDelta0AndTheSlopesSeOnTheTangent) {
  // k = 324.9 +- 3.249 N/m: delta0 = F_0 / k = 4.4906 mm, se = F_0 se_k / k^2 = 0.044906 mm;
  // the tangent is k itself everywhere: se_k
  ModelFit fit;
  fit.model = Model::linear;
  fit.names = {"k_N_per_m", "contact_z_m"};
  fit.params = Eigen::Vector2d(324.9, 0.01);
  fit.se = Eigen::Vector2d(3.249, 1e-6);
  const DerivedSe se = derived_se(result_of(fit, kF0 / 324.9));
  EXPECT_NEAR(*se.delta0_m.value, 4.4906124961526634e-05, 1e-12 * 4.49e-5);
  EXPECT_NEAR(*se.k_tangent_at_delta0_N_per_m.value, 3.249, 1e-12);
  EXPECT_NEAR(*se.k_tangent_N_per_m[0].value, 3.249, 1e-12);
}

TEST(AnalysisIndentationSe, WithoutAFitOrAFiniteStandardErrorEveryValueIsAbsentWithTheReason) {
  IndentationResult none;
  none.fit_reason = "no contact: no sample reaches I_c";
  none.k_tangent_N_per_m = {Value::absent("no contact"), Value::absent("no contact")};
  const DerivedSe a = derived_se(none);
  EXPECT_FALSE(a.delta0_m);
  EXPECT_EQ(a.delta0_m.reason, "no contact: no sample reaches I_c");
  EXPECT_EQ(a.k_tangent_at_delta0_N_per_m.reason, "no contact: no sample reaches I_c");
  ASSERT_EQ(a.k_tangent_N_per_m.size(), 2u);
  EXPECT_EQ(a.k_tangent_N_per_m[1].reason, "no contact: no sample reaches I_c");

  // a fit whose scale has no finite standard error (a singular Jacobian) gives no NaN
  const DerivedSe b =
      derived_se(result_of(hertz_fit(2.0e6, std::numeric_limits<double>::quiet_NaN()), 4.9e-4));
  EXPECT_FALSE(b.delta0_m);
  EXPECT_EQ(b.delta0_m.reason, "the fit gives no standard error");
  EXPECT_FALSE(b.k_tangent_N_per_m[0]);
}
