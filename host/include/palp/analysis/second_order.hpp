// SPDX-License-Identifier: Apache-2.0
// The second-order fit of a frequency response (issue 7, analysis-notes.md "Parametric fit"):
// G(s) = 1 / (m s^2 + b s + k), force in, displacement out, SI units.
//
//   1. linear start on the dynamic stiffness D = 1/G: Re D = k - m w^2, Im D = b w (two
//      decoupled least-squares regressions);
//   2. Sanathanan-Koerner reweighting by |G_previous|^2 (up to `sk_iterations`, stops when the
//      parameters change by less than 1e-9 relative);
//   3. weighted Levenberg-Marquardt on the stacked [Re; Im] residuals (G_k - G(j w_k)) / sigma_k
//      with the analytic Jacobian (dG/dk = -G^2, dG/db = -j w G^2, dG/dm = w^2 G^2) in
//      log-parameters, so m, b, k stay positive.
// omega_n = sqrt(k/m), zeta = b / (2 sqrt(k m)) with standard errors by the delta method from
// the covariance (J^T J)^-1 (times the normalised cost when the lines carry no sigma).
//
// Adequacy: the normalised cost chi^2 / (2n - 3) is ~1 when the model explains the data to the
// measurement's noise; `adequate` is cost <= FitOptions::adequate_cost. Lines without sigma
// (a table) are weighted by 1/|G|^2 (relative error) and then the cost is unknown (nullopt).
//
// Errors: DataError for fewer than 3 lines, a non-finite value, f <= 0, a negative sigma or a
// mix of lines with and without sigma, naming the line.
#pragma once

#include <optional>
#include <span>

#include "palp/analysis/frf.hpp"

namespace palp::analysis {

struct SecondOrderOptions {
  int sk_iterations = 10;
  int max_lm_iterations = 100;
  double adequate_cost = 4.0;   ///< normalised cost above this: the model is not adequate
};

struct SecondOrderFit {
  double m_kg = 0, b_N_s_per_m = 0, k_N_per_m = 0;
  double omega_n_rad_per_s = 0, zeta = 0;
  double m_kg_se = 0, b_N_s_per_m_se = 0, k_N_per_m_se = 0;
  double omega_n_rad_per_s_se = 0, zeta_se = 0;
  /// The linear start (step 1), for comparison.
  double m_start_kg = 0, b_start_N_s_per_m = 0, k_start_N_per_m = 0;
  std::optional<double> normalized_cost;  ///< chi^2 / (2n - 3); nullopt without sigma
  bool adequate = true;                   ///< normalized_cost <= adequate_cost (true if unknown)
  int sk_iterations = 0, lm_iterations = 0;
  bool converged = false;
  std::size_t lines = 0;
  /// The model's response at a frequency.
  std::complex<double> G(double f_Hz) const;
};

SecondOrderFit fit_second_order(std::span<const FrfLine> lines,
                                const SecondOrderOptions& options = {});

}  // namespace palp::analysis
