// SPDX-License-Identifier: Apache-2.0
// Bounded Levenberg-Marquardt: see least_squares.hpp.
#include "analysis/least_squares.hpp"

#include <algorithm>
#include <cmath>

namespace palp::analysis::detail {

namespace {

Eigen::VectorXd clamp(const Eigen::VectorXd& p, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  return p.cwiseMax(lo).cwiseMin(hi);
}

Eigen::MatrixXd jacobian(const ResidualFn& f, const JacobianFn& analytic, const Eigen::VectorXd& p,
                         Eigen::Index n, const Eigen::VectorXd& typical) {
  Eigen::MatrixXd J(n, p.size());
  if (analytic) {
    analytic(p, J);
    return J;
  }
  Eigen::VectorXd rp(n), rm(n);
  for (Eigen::Index j = 0; j < p.size(); ++j) {
    const double h = 1e-6 * std::max(std::abs(p[j]), typical[j]);
    Eigen::VectorXd q = p;
    q[j] = p[j] + h;
    f(q, rp);
    q[j] = p[j] - h;
    f(q, rm);
    J.col(j) = (rp - rm) / (2.0 * h);
  }
  return J;
}

}  // namespace

LsqResult levenberg_marquardt(const ResidualFn& f, Eigen::Index n, const Eigen::VectorXd& p0,
                              const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                              const Eigen::VectorXd& typical, const JacobianFn& analytic,
                              int max_iterations) {
  LsqResult out;
  out.p = clamp(p0, lo, hi);
  out.r.resize(n);
  f(out.p, out.r);
  out.rss = out.r.squaredNorm();
  double lambda = 1e-3;
  Eigen::VectorXd r_new(n);
  double rss_stall_ref = out.rss;  // the cost kStallIterations iterations ago
  constexpr int kStallIterations = 10;
  for (out.iterations = 0; out.iterations < max_iterations; ++out.iterations) {
    // a long, curved valley (the contact point and the modulus trade off) can take hundreds of
    // tiny steps: once ten iterations together lower the cost by less than 1e-8 of it, stop
    if (out.iterations > 0 && out.iterations % kStallIterations == 0) {
      if (rss_stall_ref - out.rss <= 1e-8 * (out.rss + 1e-300)) {
        out.converged = true;
        break;
      }
      rss_stall_ref = out.rss;
    }
    const Eigen::MatrixXd J = jacobian(f, analytic, out.p, n, typical);
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * out.r;
    Eigen::VectorXd d = A.diagonal().cwiseMax(1e-300);
    bool accepted = false;
    double step_norm = 0.0;
    for (int tries = 0; tries < 30 && !accepted; ++tries) {
      Eigen::MatrixXd M = A;
      M.diagonal() += lambda * d;
      const Eigen::VectorXd dp = M.ldlt().solve(-g);
      const Eigen::VectorXd p_new = clamp(out.p + dp, lo, hi);
      f(p_new, r_new);
      const double rss_new = r_new.squaredNorm();
      if (std::isfinite(rss_new) && rss_new <= out.rss) {
        const double decrease = out.rss - rss_new;
        step_norm = ((p_new - out.p).array() / (out.p.array().abs().max(typical.array()))).abs().maxCoeff();
        out.p = p_new;
        out.r = r_new;
        out.rss = rss_new;
        lambda = std::max(lambda * 0.3, 1e-12);
        accepted = true;
        if (decrease <= 1e-12 * (rss_new + 1e-300) || step_norm < 1e-10) {
          out.converged = true;
        }
      } else {
        lambda *= 10.0;
      }
    }
    if (!accepted) {  // no step lowers the cost: a (local) minimum within the box
      out.converged = true;
    }
    if (out.converged) break;
  }
  out.J = jacobian(f, analytic, out.p, n, typical);
  return out;
}

Eigen::VectorXd standard_errors(const Eigen::MatrixXd& J, double rss, Eigen::Index n) {
  if (n < 0) n = J.rows();
  const Eigen::Index p = J.cols();
  Eigen::VectorXd se = Eigen::VectorXd::Zero(p);
  if (n <= p) return se;
  // Scale columns so that the inverse is well conditioned whatever the units.
  Eigen::VectorXd s = J.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < p; ++j) if (!(s[j] > 0.0)) return se;
  const Eigen::MatrixXd Js = J * s.cwiseInverse().asDiagonal();
  Eigen::MatrixXd A = Js.transpose() * Js;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible()) return se;
  const Eigen::MatrixXd cov = lu.inverse() * (rss / static_cast<double>(n - p));
  for (Eigen::Index j = 0; j < p; ++j) se[j] = std::sqrt(std::max(cov(j, j), 0.0)) / s[j];
  return se;
}

}  // namespace palp::analysis::detail
