// SPDX-License-Identifier: Apache-2.0
// sphere_touch: where a spherical tip lowered along +z (or along a tilted probe axis) first
// touches a phantom's surface.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "palp/plant/phantom.hpp"

namespace palp::plant {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStopStep_m = 1e-9;     // the search ends when its step is below 1 nm
constexpr double kNewtonStep_m = 1e-6;   // finite-difference step of the Newton refinement

// The minimum of f over the disc u^2 + v^2 <= r^2 (f = +inf where there is nothing): a coarse
// polar scan, a pattern search to r/256, Newton steps on finite differences, the pattern search
// on to 1 nm where they do not improve (README.md "Sphere tip").
struct DiscMinimum {
  double u = 0.0, v = 0.0, value = kInf;
};

template <class F>
DiscMinimum minimise_on_disc(const F& touch_z, double r) {
  // Coarse polar scan: the apex, then rings at 0.4 and 0.85 of R.
  double best_u = 0.0, best_v = 0.0, best = touch_z(0.0, 0.0);
  constexpr std::array<double, 2> kRings = {0.4, 0.85};
  constexpr std::array<int, 2> kAngles = {8, 16};
  for (std::size_t k = 0; k < kRings.size(); ++k) {
    for (int j = 0; j < kAngles[k]; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / kAngles[k];
      const double u = kRings[k] * r * std::cos(phi), v = kRings[k] * r * std::sin(phi);
      const double z = touch_z(u, v);
      if (z < best) {
        best = z;
        best_u = u;
        best_v = v;
      }
    }
  }
  if (!std::isfinite(best)) return {};

  // Pattern search over the 8 neighbours (axes and diagonals) down to R/256; only a strict
  // improvement moves, so a flat top keeps the apex and its exact height.
  auto pattern_search = [&](double h, double h_end) {
    constexpr double kD = 0.70710678118654752;
    constexpr std::array<std::array<double, 2>, 8> kDirs = {
        {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {kD, kD}, {kD, -kD}, {-kD, kD}, {-kD, -kD}}};
    while (h >= h_end) {
      double cand = best, cu = best_u, cv = best_v;
      for (const auto& d : kDirs) {
        const double u = best_u + h * d[0], v = best_v + h * d[1];
        const double z = touch_z(u, v);
        if (z < cand) {
          cand = z;
          cu = u;
          cv = v;
        }
      }
      if (cand < best) {
        best = cand;
        best_u = cu;
        best_v = cv;
      } else {
        h *= 0.5;
      }
    }
    return h;
  };
  const double h_left = pattern_search(0.125 * r, r / 256.0);

  // Then Newton steps on a 9-point finite-difference gradient and Hessian (quadratic
  // convergence on smooth surfaces); where they do not improve (a kink, an edge, a flat top),
  // the pattern search goes on to 1 nm instead.
  bool converged = false;
  for (int it = 0; it < 6 && !converged; ++it) {
    const double e = kNewtonStep_m;
    const double f0 = best;
    const double fxp = touch_z(best_u + e, best_v), fxm = touch_z(best_u - e, best_v);
    const double fyp = touch_z(best_u, best_v + e), fym = touch_z(best_u, best_v - e);
    const double fpp = touch_z(best_u + e, best_v + e), fpm = touch_z(best_u + e, best_v - e);
    const double fmp = touch_z(best_u - e, best_v + e), fmm = touch_z(best_u - e, best_v - e);
    const double gx = (fxp - fxm) / (2 * e), gy = (fyp - fym) / (2 * e);
    const double hxx = (fxp - 2 * f0 + fxm) / (e * e), hyy = (fyp - 2 * f0 + fym) / (e * e);
    const double hxy = (fpp - fpm - fmp + fmm) / (4 * e * e);
    const double det = hxx * hyy - hxy * hxy;
    if (!std::isfinite(det) || !(hxx > 0.0) || !(det > 0.0)) break;
    const double du = -(hyy * gx - hxy * gy) / det, dv = -(hxx * gy - hxy * gx) / det;
    if (std::hypot(du, dv) > 0.1 * r) break;  // not in the quadratic basin yet
    const double z = touch_z(best_u + du, best_v + dv);
    if (!(z <= best)) {
      converged = std::hypot(du, dv) < kStopStep_m;  // at the bottom: rounding only
      break;
    }
    best = z;
    best_u += du;
    best_v += dv;
    converged = std::hypot(du, dv) < kStopStep_m;
  }
  if (!converged) pattern_search(h_left, kStopStep_m);

  return {best_u, best_v, best};
}

// A vertical probe: the apex height at which the sphere's point above (x + u, y + v) meets the
// surface. The sag R - sqrt(R^2 - rho^2) is written as rho^2 / (R + sqrt(R^2 - rho^2)): exact 0
// at the apex.
SphereTouch touch_from_z(const Phantom& phantom, double x_m, double y_m, double r) {
  const double r2 = r * r;
  auto touch_z = [&](double u, double v) {
    const double rho2 = u * u + v * v;
    if (rho2 > r2) return kInf;
    const double zs = phantom.surface_z_m(x_m + u, y_m + v);
    if (!std::isfinite(zs)) return kInf;
    return zs + rho2 / (r + std::sqrt(r2 - rho2));
  };
  const DiscMinimum m = minimise_on_disc(touch_z, r);
  SphereTouch out;
  if (!std::isfinite(m.value)) {
    out.apex_z_m = out.point_z_m = kInf;
    return out;
  }
  out.touches = true;
  out.apex_z_m = m.value;
  out.point_x_m = x_m + m.u;
  out.point_y_m = y_m + m.v;
  out.point_z_m = phantom.surface_z_m(out.point_x_m, out.point_y_m);
  const double w = std::sqrt(std::max(0.0, r2 - m.u * m.u - m.v * m.v));
  out.normal = {m.u / r, m.v / r, w / r};
  return out;
}

// Where the line b + t axis crosses the surface: Newton on g(t) = b_z + t a_z - z_s(b + t a)
// with a forward-difference slope (exact on planes), to 1e-13 m; +inf where it leaves the
// footprint or does not converge.
double crossing(const Phantom& phantom, const std::array<double, 3>& b,
                const std::array<double, 3>& a) {
  auto g = [&](double t) {
    return b[2] + t * a[2] - phantom.surface_z_m(b[0] + t * a[0], b[1] + t * a[1]);
  };
  const double z0 = phantom.surface_z_m(b[0], b[1]);
  if (!std::isfinite(z0)) return kInf;
  double t = (z0 - b[2]) / a[2];
  constexpr double kH = 1e-7;
  for (int it = 0; it < 30; ++it) {
    const double g0 = g(t), g1 = g(t + kH);
    if (!std::isfinite(g0) || !std::isfinite(g1)) return kInf;
    const double slope = (g1 - g0) / kH;
    if (!(slope > 0.0)) return kInf;  // the axis runs along or out of the surface
    const double dt = -g0 / slope;
    t += dt;
    if (std::abs(dt) < 1e-13) return t;
  }
  return kInf;
}

bool is_vertical(const std::array<double, 3>& axis) {
  return axis[0] == 0.0 && axis[1] == 0.0 && axis[2] == 1.0;
}

}  // namespace

SphereTouch sphere_touch(const Phantom& phantom, double x_m, double y_m, double radius_m) {
  if (!(radius_m > 0.0)) throw std::invalid_argument("sphere_touch: radius must be positive");
  return touch_from_z(phantom, x_m, y_m, radius_m);
}

double surface_along_axis_m(const Phantom& phantom, double x_m, double y_m,
                            const std::array<double, 3>& axis) {
  if (is_vertical(axis)) return phantom.surface_z_m(x_m, y_m);
  return crossing(phantom, {x_m, y_m, 0.0}, axis);
}

SphereTouch sphere_touch_along(const Phantom& phantom, double x_m, double y_m,
                               const std::array<double, 3>& axis, double radius_m) {
  if (!(radius_m > 0.0)) throw std::invalid_argument("sphere_touch: radius must be positive");
  if (!(axis[2] > 0.0) || std::abs(std::hypot(axis[0], axis[1], axis[2]) - 1.0) > 1e-9) {
    throw std::invalid_argument("sphere_touch_along: the axis must be a unit vector with z > 0");
  }
  if (is_vertical(axis)) return touch_from_z(phantom, x_m, y_m, radius_m);
  const double r = radius_m, r2 = r * r;
  // e1, e2: the plane across the axis
  const double n1 = std::hypot(axis[0], axis[2]);
  const std::array<double, 3> e1 = {axis[2] / n1, 0.0, -axis[0] / n1};
  const std::array<double, 3> e2 = {axis[1] * e1[2] - axis[2] * e1[1],
                                    axis[2] * e1[0] - axis[0] * e1[2],
                                    axis[0] * e1[1] - axis[1] * e1[0]};
  auto base = [&](double p, double q) {
    return std::array<double, 3>{x_m + p * e1[0] + q * e2[0], y_m + p * e1[1] + q * e2[1],
                                 p * e1[2] + q * e2[2]};
  };
  // the apex's axial position at which the sphere's point at (p, q) across the axis meets the
  // surface: the surface's crossing on that line plus the sag
  auto touch_t = [&](double p, double q) {
    const double rho2 = p * p + q * q;
    if (rho2 > r2) return kInf;
    const double t = crossing(phantom, base(p, q), axis);
    if (!std::isfinite(t)) return kInf;
    return t + rho2 / (r + std::sqrt(r2 - rho2));
  };
  const DiscMinimum m = minimise_on_disc(touch_t, r);
  SphereTouch out;
  if (!std::isfinite(m.value)) {
    out.apex_z_m = out.point_z_m = kInf;
    return out;
  }
  const double w = std::sqrt(std::max(0.0, r2 - m.u * m.u - m.v * m.v));
  const std::array<double, 3> b = base(m.u, m.v);
  const double t_point = m.value - (r - w);  // the touched point's axial position
  out.touches = true;
  out.apex_z_m = m.value * axis[2];
  out.point_x_m = b[0] + t_point * axis[0];
  out.point_y_m = b[1] + t_point * axis[1];
  out.point_z_m = phantom.surface_z_m(out.point_x_m, out.point_y_m);
  for (int i = 0; i < 3; ++i) out.normal[i] = (m.u * e1[i] + m.v * e2[i] + w * axis[i]) / r;
  return out;
}

}  // namespace palp::plant
