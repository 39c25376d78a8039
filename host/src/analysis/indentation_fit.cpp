// SPDX-License-Identifier: Apache-2.0
// Model fits with the contact point as a parameter: see palp/analysis/indentation.hpp.
//
// Start: a profile over z_c on a grid (for each candidate z_c the model is linear in its
// stiffness parameter and offset, solved in closed form); then Levenberg-Marquardt on all
// parameters. The Sneddon fit starts from the Hertz solution. Deterministic, no state.
// Every point carries a weight (1 for a sample, the sample count for a plateau mean): the
// residuals are sqrt(w) (F - model).
#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/indentation_internal.hpp"
#include "analysis/least_squares.hpp"
#include "palp/error.hpp"

namespace palp::analysis {

namespace {

using detail::FitData;

// The model's object force per unit stiffness parameter (k or E*), thickness included.
double unit_force(Model m, double depth, double R, const std::optional<Thickness>& t) {
  if (!(depth > 0.0)) return 0.0;
  double f = 0.0;
  switch (m) {
    case Model::linear: return depth;
    case Model::hertz: f = hertz_force_N(depth, 1.0, R); break;
    case Model::sneddon: f = sneddon_force_N(depth, 1.0, R); break;
  }
  return t ? f * thickness_factor(depth, R, *t) : f;
}

// It and its derivative with respect to depth (for the analytic Jacobian), from one Sneddon
// solve.
ForceStiffness unit_law(Model m, double depth, double R, const std::optional<Thickness>& t) {
  if (!(depth > 0.0)) return {};
  ForceStiffness u;
  switch (m) {
    case Model::linear: return {depth, 1.0};
    case Model::hertz: u = {hertz_force_N(depth, 1.0, R), hertz_stiffness_N_per_m(depth, 1.0, R)}; break;
    case Model::sneddon: u = sneddon_force_stiffness(depth, 1.0, R); break;
  }
  if (!t) return u;
  return {u.force_N * thickness_factor(depth, R, *t),
          u.stiffness_N_per_m * thickness_factor(depth, R, *t) +
              u.force_N * thickness_factor_derivative_per_m(depth, R, *t)};
}

double unit_stiffness(Model m, double depth, double R, const std::optional<Thickness>& t) {
  return unit_law(m, depth, R, t).stiffness_N_per_m;
}

// Its second derivative (how a plateau's slope moves with z_c); u: unit_law at this depth.
double unit_curvature(Model m, double depth, double R, const std::optional<Thickness>& t,
                      const ForceStiffness& u) {
  if (!(depth > 0.0) || m == Model::linear) return 0.0;
  if (t) {  // the thickness factor's product rule: a central difference of the slope
    const double h = 1e-6 * std::max(depth, 1e-3 * R);
    return (unit_stiffness(m, depth + h, R, t) - unit_stiffness(m, std::max(depth - h, 0.0), R, t)) /
           (depth + h - std::max(depth - h, 0.0));
  }
  if (m == Model::hertz) return std::sqrt(R / depth);  // d/ddelta of 2 sqrt(R delta)
  // Sneddon: dF/ddelta = 2 a, and ddelta/da = atanh(a/R) + (a/R) / (1 - (a/R)^2)
  const double a_over_R = 0.5 * u.stiffness_N_per_m / R;
  if (!(a_over_R < 1.0)) return 0.0;
  return 2.0 / (std::atanh(a_over_R) + a_over_R / (1.0 - a_over_R * a_over_R));
}

struct Setup {
  Model model;
  bool offset;
  double kv, R;
  std::optional<Thickness> thickness;
  const detail::FitPoints* d;
  Eigen::VectorXd sqrt_w;
};

// Residuals: sqrt(w) (F - model) at each point, then on plateaus one more per plateau,
// sqrt(szz) (slope - szf / szz) with slope = k_v + theta g'(delta): the samples' squared
// residuals inside a plateau are szz (slope - szf/szz)^2 + (sff - szf^2/szz) to second order,
// so the fit minimises the samples fit's cost (FitPoints::scatter_floor is the constant rest).
Eigen::Index residual_count(const Setup& s) {
  return s.d->on == FitOn::plateaus ? 2 * s.d->z_m.size() : s.d->z_m.size();
}

void residuals(const Setup& s, const Eigen::VectorXd& q, Eigen::VectorXd& r) {
  const double theta = q[0], zc = q[1], c = s.offset ? q[2] : 0.0;
  const auto& z = s.d->z_m;
  const auto& F = s.d->F_N;
  const Eigen::Index n = z.size();
  const bool within = s.d->on == FitOn::plateaus;
  r.resize(residual_count(s));
  for (Eigen::Index k = 0; k < n; ++k) {
    const double delta = z[k] - zc;
    if (!within) {
      r[k] = s.sqrt_w[k] * (F[k] - (s.kv * delta + theta * unit_force(s.model, delta, s.R, s.thickness) + c));
      continue;
    }
    const ForceStiffness u = unit_law(s.model, delta, s.R, s.thickness);
    r[k] = s.sqrt_w[k] * (F[k] - (s.kv * delta + theta * u.force_N + c));
    const double szz = s.d->szz[k];
    r[n + k] = szz > 0.0 ? std::sqrt(szz) * (s.kv + theta * u.stiffness_N_per_m - s.d->szf[k] / szz) : 0.0;
  }
}

// dr/dtheta = -g(delta), dr/dz_c = k_v + theta g'(delta), dr/dc = -1 (each times sqrt(w)); the
// plateau rows: sqrt(szz) g'(delta) and -sqrt(szz) theta g''(delta).
void jacobian(const Setup& s, const Eigen::VectorXd& q, Eigen::MatrixXd& J) {
  const auto& z = s.d->z_m;
  const Eigen::Index n = z.size();
  const bool within = s.d->on == FitOn::plateaus;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double delta = z[k] - q[1];
    const ForceStiffness u = unit_law(s.model, delta, s.R, s.thickness);
    J(k, 0) = -s.sqrt_w[k] * u.force_N;
    J(k, 1) = s.sqrt_w[k] * (s.kv + q[0] * u.stiffness_N_per_m);
    if (s.offset) J(k, 2) = -s.sqrt_w[k];
    if (!within) continue;
    const double root = std::sqrt(s.d->szz[k]);
    J(n + k, 0) = root * u.stiffness_N_per_m;
    J(n + k, 1) = root > 0.0 ? -root * q[0] * unit_curvature(s.model, delta, s.R, s.thickness, u) : 0.0;
    if (s.offset) J(n + k, 2) = 0.0;
  }
}

// Closed-form (theta, c) for a fixed z_c; returns the weighted rss.
double profile(const Setup& s, double zc, double& theta, double& c) {
  const auto& z = s.d->z_m;
  const auto& F = s.d->F_N;
  const auto& w = s.d->w;
  const Eigen::Index n = z.size();
  double sw = 0, sg = 0, sy = 0, sgg = 0, sgy = 0, syy = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double delta = z[k] - zc;
    const double g = unit_force(s.model, delta, s.R, s.thickness);
    const double y = F[k] - s.kv * delta;
    sw += w[k]; sg += w[k] * g; sy += w[k] * y; sgg += w[k] * g * g; sgy += w[k] * g * y; syy += w[k] * y * y;
  }
  if (s.offset) {
    const double det = sw * sgg - sg * sg;
    if (!(det > 0.0)) { theta = 0; c = sy / sw; return syy - sy * sy / sw; }
    theta = (sw * sgy - sg * sy) / det;
    c = (sy - theta * sg) / sw;
  } else {
    c = 0.0;
    theta = sgg > 0.0 ? sgy / sgg : 0.0;
  }
  // the least-squares optimum's rss in closed form (no second pass over the model)
  return std::max(syy - theta * sgy - c * sy, 0.0);
}

struct Range { double lo, hi; std::string method; };

// The profile start puts a good fit within a few iterations (3-5 on the paper's curves); a
// curve the model does not describe well can creep along a curved valley of (E*, z_c) for
// hundreds of small steps instead. 60 bound the time (a map analyses thousands of fits); the
// fit then says it did not converge (ModelFit::converged) and keeps its best point.
constexpr int kMaxFitIterations = 60;

Range contact_range(const FitData& d) {
  const double zmin = d.points.z_m.minCoeff(), zmax = d.points.z_m.maxCoeff();
  const double span = std::max(zmax - zmin, 1e-9);
  if (d.has_baseline) {
    return {zmin, zmax - 0.1 * span,
            "baseline present: profile over the data range, then refined by the fit"};
  }
  const double first = *std::min_element(d.first_contact_z_m.begin(), d.first_contact_z_m.end());
  return {zmin - 0.1 * span, std::min(first + 0.1 * span, zmax - 0.1 * span),
          "no baseline: profile around the first sample at i >= I_c, then refined by the fit"};
}

ModelFit finish(const Setup& s, const detail::LsqResult& lm, const IndentationParams& p,
                const std::string& method) {
  ModelFit m;
  m.model = s.model;
  m.names = {s.model == Model::linear ? "k_N_per_m" : "Estar_Pa", "contact_z_m"};
  if (s.offset) m.names.push_back("offset_N");
  m.params = lm.p;
  const detail::FitPoints& pts = *s.d;
  const double rss = lm.rss + pts.scatter_floor();  // every sample's residual (see residuals)
  m.n = static_cast<int>(std::lround(pts.n_samples()));
  m.n_points = static_cast<int>(pts.z_m.size());
  m.se = detail::standard_errors(lm.J, rss, m.n);
  m.rss = rss;
  const int np = static_cast<int>(lm.p.size());
  m.aic = m.n * std::log(std::max(rss, 1e-300) / m.n) + 2.0 * np;
  m.rms_residual_N = m.n > np ? std::sqrt(rss / (m.n - np)) : 0.0;
  if (p.force_noise_N && *p.force_noise_N > 0.0)
    m.reduced_chi2 = m.rms_residual_N * m.rms_residual_N / (*p.force_noise_N * *p.force_noise_N);
  // R^2 of the object force F_o = F - k_v (z - z_c) (residuals are the same as for F), its
  // total sum of squares over the samples from the points' means and scatter
  const Eigen::ArrayXd Fo = pts.F_N.array() - s.kv * (pts.z_m.array() - lm.p[1]);
  const double mean = (pts.w.array() * Fo).sum() / pts.w.sum();
  const double tss = (pts.w.array() * (Fo - mean).square()).sum() +
                     (pts.sff.array() - 2.0 * s.kv * pts.szf.array() + s.kv * s.kv * pts.szz.array()).sum();
  m.r2 = tss > 0.0 ? 1.0 - rss / tss : 0.0;
  m.contact_z_m = lm.p[1];
  m.contact_z_se_m = m.se[1];
  if (s.model == Model::linear) {
    m.k_N_per_m = lm.p[0];
  } else {
    m.Estar_Pa = lm.p[0];
    m.E_Pa = youngs_modulus_Pa(lm.p[0], p.poisson);
  }
  if (s.offset) m.offset_N = lm.p[2];
  m.converged = lm.converged;
  m.iterations = lm.iterations;
  m.contact_method = method;
  m.radius_m = s.R;
  m.thickness = s.model == Model::linear ? std::nullopt : s.thickness;
  return m;
}

}  // namespace

double detail::FitPoints::scatter_floor() const {
  double sum = 0.0;
  for (Eigen::Index k = 0; k < sff.size(); ++k)
    sum += szz[k] > 0.0 ? std::max(sff[k] - szf[k] * szf[k] / szz[k], 0.0) : sff[k];
  return sum;
}

ModelFit detail::fit_model(Model model, const FitData& d, const IndentationParams& p,
                           const ModelFit* start) {
  Setup s{model, d.has_baseline && model != Model::linear, p.spring_N_per_m, p.tip_radius_m,
          model == Model::linear ? std::nullopt : p.thickness, &d.points, d.points.w.cwiseSqrt()};
  const Range range = contact_range(d);
  double theta = 0.0, off = 0.0, zc = 0.0;
  if (start) {
    theta = start->params[0];
    zc = start->contact_z_m;
    off = start->offset_N.value_or(0.0);
  } else {
    // Coarse grid, then a fine grid around the best cell.
    double best = INFINITY, lo = range.lo, hi = range.hi;
    for (int pass = 0; pass < 2; ++pass) {
      const int N = pass == 0 ? 120 : 40;
      const double step = (hi - lo) / N;
      double best_z = zc;
      for (int k = 0; k <= N; ++k) {
        double th, cc;
        const double zk = lo + k * step;
        const double rss = profile(s, zk, th, cc);
        if (rss < best && th > 0.0) { best = rss; best_z = zk; theta = th; off = cc; }
      }
      zc = best_z;
      lo = std::max(range.lo, zc - step);
      hi = std::min(range.hi, zc + step);
    }
    if (!(theta > 0.0)) {
      throw DataError(std::string("cannot start the ") + model_name(model) +
                        " fit: no contact point in the data range gives a positive stiffness");
    }
  }
  const int np = s.offset ? 3 : 2;
  Eigen::VectorXd p0(np), lo(np), hi(np), typ(np);
  // element by element: with the offset the vectors hold three (a comma initializer must fill all)
  p0[0] = theta;
  p0[1] = zc;
  lo[0] = 0.0;
  lo[1] = range.lo;
  hi[0] = INFINITY;
  hi[1] = range.hi;
  const double span = std::max(d.points.z_m.maxCoeff() - d.points.z_m.minCoeff(), 1e-6);
  typ[0] = std::abs(theta) + 1e-12;
  typ[1] = span;
  if (s.offset) {
    p0[2] = off; lo[2] = -INFINITY; hi[2] = INFINITY;
    typ[2] = std::max(d.points.F_N.cwiseAbs().maxCoeff(), 1e-6);
  }
  const auto lm = detail::levenberg_marquardt(
      [&](const Eigen::VectorXd& q, Eigen::VectorXd& r) { residuals(s, q, r); }, residual_count(s), p0,
      lo, hi, typ, [&](const Eigen::VectorXd& q, Eigen::MatrixXd& J) { jacobian(s, q, J); },
      kMaxFitIterations);
  return finish(s, lm, p, start ? start->contact_method : range.method);
}

const char* model_name(Model m) {
  switch (m) {
    case Model::linear: return "linear";
    case Model::hertz: return "hertz";
    case Model::sneddon: return "sneddon";
  }
  return "?";
}

double ModelFit::force_N(double depth_m) const {
  return params[0] * unit_force(model, depth_m, radius_m, thickness);
}

double ModelFit::stiffness_N_per_m(double depth_m) const {
  if (!(depth_m > 0.0)) return model == Model::linear ? params[0] : 0.0;
  return params[0] * unit_stiffness(model, depth_m, radius_m, thickness);
}

namespace {

detail::FitData collect_with_contact(const Curve& c, const IndentationParams& p) {
  detail::FitData d = detail::collect_loading(c, p);
  detail::require_contact(d, p);
  return d;
}

}  // namespace

ModelFit fit_linear(const Curve& c, const IndentationParams& p) {
  return detail::fit_model(Model::linear, collect_with_contact(c, p), p);
}
ModelFit fit_hertz(const Curve& c, const IndentationParams& p) {
  return detail::fit_model(Model::hertz, collect_with_contact(c, p), p);
}
ModelFit fit_sneddon(const Curve& c, const IndentationParams& p) {
  const detail::FitData d = collect_with_contact(c, p);
  const ModelFit h = detail::fit_model(Model::hertz, d, p);
  return detail::fit_model(Model::sneddon, d, p, &h);
}

}  // namespace palp::analysis
