// SPDX-License-Identifier: Apache-2.0
// sphere_touch: where a spherical tip lowered along +z first touches a phantom's surface.
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

}  // namespace

SphereTouch sphere_touch(const Phantom& phantom, double x_m, double y_m, double radius_m) {
  if (!(radius_m > 0.0)) throw std::invalid_argument("sphere_touch: radius must be positive");
  const double r = radius_m;
  const double r2 = r * r;
  // Apex height at which the sphere's point above (x + u, y + v) meets the surface. The sag
  // R - sqrt(R^2 - rho^2) is written as rho^2 / (R + sqrt(R^2 - rho^2)): exact 0 at the apex.
  auto touch_z = [&](double u, double v) {
    const double rho2 = u * u + v * v;
    if (rho2 > r2) return kInf;
    const double zs = phantom.surface_z_m(x_m + u, y_m + v);
    if (!std::isfinite(zs)) return kInf;
    return zs + rho2 / (r + std::sqrt(r2 - rho2));
  };

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
  SphereTouch out;
  if (!std::isfinite(best)) {
    out.apex_z_m = out.point_z_m = kInf;
    return out;
  }

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

  out.touches = true;
  out.apex_z_m = best;
  out.point_x_m = x_m + best_u;
  out.point_y_m = y_m + best_v;
  out.point_z_m = phantom.surface_z_m(out.point_x_m, out.point_y_m);
  const double w = std::sqrt(std::max(0.0, r2 - best_u * best_u - best_v * best_v));
  out.normal = {best_u / r, best_v / r, w / r};
  return out;
}

}  // namespace palp::plant
