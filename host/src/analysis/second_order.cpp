// SPDX-License-Identifier: Apache-2.0
// The second-order fit: linear start on D = 1/G, Sanathanan-Koerner, weighted LM in
// log-parameters (see second_order.hpp).
#include "palp/analysis/second_order.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "analysis/least_squares.hpp"
#include "palp/error.hpp"

namespace palp::analysis {

namespace {

using cd = std::complex<double>;

struct Params {
  double m = 0, b = 0, k = 0;
};

cd model_G(const Params& p, double w) { return 1.0 / cd(p.k - p.m * w * w, p.b * w); }

double omega(double f_Hz) { return 2.0 * std::numbers::pi * f_Hz; }

std::string line_name(std::size_t i, double f_Hz) {
  std::ostringstream s;
  s << "line " << i + 1 << " (f_Hz " << f_Hz << ")";
  return s.str();
}

/// DataError for anything the fit cannot use; true when the lines carry sigma.
bool check_lines(std::span<const FrfLine> lines) {
  if (lines.size() < 3)
    throw DataError("the second-order fit needs at least 3 lines, got " +
                      std::to_string(lines.size()));
  std::size_t with_sigma = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const FrfLine& l = lines[i];
    if (!std::isfinite(l.f_Hz) || !std::isfinite(l.G_m_per_N.real()) ||
        !std::isfinite(l.G_m_per_N.imag()) || !std::isfinite(l.sigma_m_per_N))
      throw DataError("second-order fit: " + line_name(i, l.f_Hz) + " has a non-finite value");
    if (l.f_Hz <= 0)
      throw DataError("second-order fit: " + line_name(i, l.f_Hz) +
                        " has a frequency that is not positive");
    if (l.sigma_m_per_N < 0)
      throw DataError("second-order fit: " + line_name(i, l.f_Hz) + " has a negative sigma");
    if (l.G_m_per_N == cd(0, 0))
      throw DataError("second-order fit: " + line_name(i, l.f_Hz) + " has G = 0");
    if (l.sigma_m_per_N > 0) ++with_sigma;
  }
  if (with_sigma != 0 && with_sigma != lines.size()) {
    for (std::size_t i = 0; i < lines.size(); ++i)
      if ((lines[i].sigma_m_per_N > 0) != (lines[0].sigma_m_per_N > 0))
        throw DataError("second-order fit: " + line_name(i, lines[i].f_Hz) +
                          (lines[0].sigma_m_per_N > 0 ? " has no sigma" : " has a sigma") +
                          " where line 1 " + (lines[0].sigma_m_per_N > 0 ? "has one" : "has none") +
                          "; give every line a sigma or none");
  }
  return with_sigma == lines.size();
}

/// Solves the real least-squares problem A x = y (3 unknowns) by QR.
Eigen::Vector3d solve3(const Eigen::MatrixXd& A, const Eigen::VectorXd& y) {
  return A.colPivHouseholderQr().solve(y);
}

/// Step 1: Re D = k - m w^2 and Im D = b w, two unweighted regressions.
Params linear_start(std::span<const FrfLine> lines) {
  const auto n = static_cast<Eigen::Index>(lines.size());
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd y(n);
  double sww = 0, swy = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = omega(lines[static_cast<std::size_t>(i)].f_Hz);
    const cd D = 1.0 / lines[static_cast<std::size_t>(i)].G_m_per_N;
    A(i, 0) = 1.0;
    A(i, 1) = -w * w;
    y[i] = D.real();
    sww += w * w;
    swy += w * D.imag();
  }
  const Eigen::Vector2d km = A.colPivHouseholderQr().solve(y);
  return {km[1], swy / sww, km[0]};
}

/// Replaces non-positive or non-finite parameters by small positive ones of the data's scale,
/// so the log-parameter fit can start.
Params make_positive(Params p, std::span<const FrfLine> lines) {
  double mean_D = 0, w_max = 0;
  for (const FrfLine& l : lines) {
    mean_D += std::abs(1.0 / l.G_m_per_N) / static_cast<double>(lines.size());
    w_max = std::max(w_max, omega(l.f_Hz));
  }
  if (!(p.k > 0) || !std::isfinite(p.k)) p.k = mean_D;
  if (!(p.m > 0) || !std::isfinite(p.m)) p.m = 1e-3 * p.k / (w_max * w_max);
  if (!(p.b > 0) || !std::isfinite(p.b)) p.b = 2e-3 * std::sqrt(p.k * p.m);
  return p;
}

/// One Sanathanan-Koerner step: minimises sum |(A(jw) G_k - 1) / (A_prev(jw) s_k)|^2, linear in
/// (m, b, k), with A = k - m w^2 + j b w and s_k the line's scale (sigma, or |G_k|).
Params sk_step(std::span<const FrfLine> lines, const std::vector<double>& scale, const Params& prev) {
  const auto n = static_cast<Eigen::Index>(lines.size());
  Eigen::MatrixXd A(2 * n, 3);
  Eigen::VectorXd y(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double w = omega(lines[u].f_Hz);
    const cd G = lines[u].G_m_per_N;
    const double weight = std::abs(model_G(prev, w)) / scale[u];
    const cd cm = -w * w * G * weight, cb = cd(0, w) * G * weight, ck = G * weight;
    A.row(i) << cm.real(), cb.real(), ck.real();
    A.row(n + i) << cm.imag(), cb.imag(), ck.imag();
    y[i] = weight;
    y[n + i] = 0.0;
  }
  const Eigen::Vector3d x = solve3(A, y);
  return {x[0], x[1], x[2]};
}

double relative_change(const Params& a, const Params& b) {
  return std::max({std::abs(a.m - b.m) / std::abs(b.m), std::abs(a.b - b.b) / std::abs(b.b),
                   std::abs(a.k - b.k) / std::abs(b.k)});
}

}  // namespace

std::complex<double> SecondOrderFit::G(double f_Hz) const {
  return model_G({m_kg, b_N_s_per_m, k_N_per_m}, omega(f_Hz));
}

SecondOrderFit fit_second_order(std::span<const FrfLine> lines, const SecondOrderOptions& options) {
  const bool has_sigma = check_lines(lines);
  SecondOrderFit out;
  out.lines = lines.size();
  std::vector<double> scale(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i)
    scale[i] = has_sigma ? lines[i].sigma_m_per_N : std::abs(lines[i].G_m_per_N);

  // 1. linear start
  const Params start = linear_start(lines);
  out.m_start_kg = start.m;
  out.b_start_N_s_per_m = start.b;
  out.k_start_N_per_m = start.k;

  // 2. Sanathanan-Koerner, from the linear start as it is (a negative k from noisy lines far
  // from resonance still gives usable weights |G_previous|)
  Params p = start;
  if (!std::isfinite(p.m + p.b + p.k)) p = make_positive(p, lines);
  for (int it = 0; it < options.sk_iterations; ++it) {
    const Params next = sk_step(lines, scale, p);
    if (!std::isfinite(next.m + next.b + next.k)) break;
    out.sk_iterations = it + 1;
    const double change = relative_change(next, p);
    p = next;
    if (change < 1e-9) break;
  }
  p = make_positive(p, lines);

  // 3. weighted LM on [Re; Im] of (G_k - G(jw_k)) / s_k in q = (ln m, ln b, ln k)
  const auto n = static_cast<Eigen::Index>(lines.size());
  const auto residuals = [&](const Eigen::VectorXd& q, Eigen::VectorXd& r) {
    const Params t{std::exp(q[0]), std::exp(q[1]), std::exp(q[2])};
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const cd e = (lines[u].G_m_per_N - model_G(t, omega(lines[u].f_Hz))) / scale[u];
      r[i] = e.real();
      r[n + i] = e.imag();
    }
  };
  const auto jacobian = [&](const Eigen::VectorXd& q, Eigen::MatrixXd& J) {
    const Params t{std::exp(q[0]), std::exp(q[1]), std::exp(q[2])};
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      const double w = omega(lines[u].f_Hz);
      const cd G = model_G(t, w), G2 = G * G;
      // r = (G_k - G) / s: dr/dln(theta) = -theta dG/dtheta / s
      const cd dm = -(w * w * G2) * t.m / scale[u];
      const cd db = -(cd(0, -w) * G2) * t.b / scale[u];
      const cd dk = -(-G2) * t.k / scale[u];
      J.row(i) << dm.real(), db.real(), dk.real();
      J.row(n + i) << dm.imag(), db.imag(), dk.imag();
    }
  };
  const Eigen::Vector3d q0(std::log(p.m), std::log(p.b), std::log(p.k));
  const Eigen::Vector3d span = Eigen::Vector3d::Constant(30.0);
  const detail::LsqResult lsq =
      detail::levenberg_marquardt(residuals, 2 * n, q0, q0 - span, q0 + span,
                                  Eigen::Vector3d::Ones(), jacobian, options.max_lm_iterations);
  out.lm_iterations = lsq.iterations;
  out.converged = lsq.converged;
  out.m_kg = std::exp(lsq.p[0]);
  out.b_N_s_per_m = std::exp(lsq.p[1]);
  out.k_N_per_m = std::exp(lsq.p[2]);
  out.omega_n_rad_per_s = std::sqrt(out.k_N_per_m / out.m_kg);
  out.zeta = out.b_N_s_per_m / (2.0 * std::sqrt(out.k_N_per_m * out.m_kg));

  const double dof = static_cast<double>(2 * n - 3);
  const double cost = lsq.rss / dof;
  if (has_sigma) {
    out.normalized_cost = cost;
    out.adequate = cost <= options.adequate_cost;
  }

  // covariance of q: (J^T J)^-1, times the normalised cost when the weights are relative only
  const Eigen::Matrix3d JtJ = lsq.J.transpose() * lsq.J;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(JtJ);
  if (lu.isInvertible()) {
    const Eigen::Matrix3d C = lu.inverse() * (has_sigma ? 1.0 : cost);
    const auto se_of = [&](const Eigen::Vector3d& g) {  // sd of g . q
      return std::sqrt(std::max(g.dot(C * g), 0.0));
    };
    out.m_kg_se = out.m_kg * se_of({1, 0, 0});
    out.b_N_s_per_m_se = out.b_N_s_per_m * se_of({0, 1, 0});
    out.k_N_per_m_se = out.k_N_per_m * se_of({0, 0, 1});
    // ln w_n = (ln k - ln m)/2; ln zeta = ln b - (ln k + ln m)/2 - ln 2
    out.omega_n_rad_per_s_se = out.omega_n_rad_per_s * se_of({-0.5, 0, 0.5});
    out.zeta_se = out.zeta * se_of({-0.5, 1, -0.5});
  }
  return out;
}

}  // namespace palp::analysis
