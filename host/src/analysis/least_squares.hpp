// SPDX-License-Identifier: Apache-2.0
// A small bounded Levenberg-Marquardt over Eigen (private to the analysis).
#pragma once

#include <Eigen/Dense>
#include <functional>

namespace palp::analysis::detail {

/// residuals(p, r): fills r (size fixed by the caller's first call) for parameters p.
using ResidualFn = std::function<void(const Eigen::VectorXd& p, Eigen::VectorXd& r)>;
/// jacobian(p, J): fills J = dr/dp (n x p); when empty, central differences are used.
using JacobianFn = std::function<void(const Eigen::VectorXd& p, Eigen::MatrixXd& J)>;

struct LsqResult {
  Eigen::VectorXd p;
  Eigen::VectorXd r;
  Eigen::MatrixXd J;  ///< at the solution
  double rss = 0.0;
  bool converged = false;
  int iterations = 0;
};

/// Minimises |r(p)|^2 with p kept inside [lo, hi] (steps are projected onto the box).
/// Marquardt's diagonal scaling makes it invariant to parameter units; the Jacobian is analytic
/// when given, else by central differences with steps 1e-6 * max(|p_j|, typical_j).
LsqResult levenberg_marquardt(const ResidualFn& residuals, Eigen::Index n_residuals,
                              const Eigen::VectorXd& p0, const Eigen::VectorXd& lo,
                              const Eigen::VectorXd& hi, const Eigen::VectorXd& typical,
                              const JacobianFn& jacobian = {}, int max_iterations = 200);

/// Standard errors sqrt(diag((J^T J)^-1) * rss / (n - p)); 0 where not identifiable.
/// n: the observations (J's rows unless given: a fit on weighted means counts their samples).
Eigen::VectorXd standard_errors(const Eigen::MatrixXd& J, double rss, Eigen::Index n = -1);

}  // namespace palp::analysis::detail
