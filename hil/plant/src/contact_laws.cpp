// SPDX-License-Identifier: Apache-2.0
// Elastic sphere laws: Hertz, exact Sneddon sphere, Dimitriadis bottom effect, series spring.
#include <algorithm>
#include <cmath>

#include "palp/plant/contact.hpp"

namespace palp::plant {
namespace {

// f(u) = u atanh(u) - d is increasing and convex on [0, 1); Newton from a point with f >= 0
// decreases monotonically to the root. sqrt(d) and tanh(d + 1) both have f >= 0.
double safe_start(double d) { return std::min(std::sqrt(d), std::tanh(d + 1.0)); }

// atanh(u) for 0 <= u < 1, several times a tick in contact: from 0.1 on as log((1 + u) / (1 - u)) / 2,
// which the library's fast log makes about three times cheaper than its atanh (a log1p); the
// argument rounds by at most 1.5 ulp, so the result is within 4e-16 of atanh(u) absolute and
// 4e-15 relative. Below 0.1 that relative error would grow as 1/u (and Newton's 1e-13 test on
// u would stall near 0): std::atanh there.
double atanh_unit(double u) { return u >= 0.1 ? 0.5 * std::log((1.0 + u) / (1.0 - u)) : std::atanh(u); }

}  // namespace

ElasticPoint hertz_sphere(double e_star_Pa, double radius_m, double depth_m) {
  if (!(depth_m > 0.0)) return {};
  const double root = std::sqrt(radius_m * depth_m);
  return {4.0 / 3.0 * e_star_Pa * root * depth_m, 2.0 * e_star_Pa * root};
}

double sneddon_contact_radius(double radius_m, double depth_m, double hint_u) {
  if (!(depth_m > 0.0)) return 0.0;
  const double d = depth_m / radius_m;
  double u = (hint_u > 0.0 && hint_u < 1.0) ? hint_u : safe_start(d);
  bool restarted = !(hint_u > 0.0 && hint_u < 1.0);
  for (int iter = 0; iter < 100; ++iter) {
    const double at = atanh_unit(u);
    const double f = u * at - d;
    const double fp = at + u / (1.0 - u * u);
    const double next = u - f / fp;
    if (!(next > 0.0 && next < 1.0)) {
      if (restarted) break;  // cannot happen from the safe start; keep the last iterate
      u = safe_start(d);
      restarted = true;
      continue;
    }
    const double step = std::abs(next - u);
    u = next;
    if (step <= 1e-13 * u) break;
  }
  return u * radius_m;
}

ElasticPoint sneddon_sphere(double e_star_Pa, double radius_m, double depth_m, double* hint_u) {
  if (!(depth_m > 0.0)) return {};
  const double a = sneddon_contact_radius(radius_m, depth_m, hint_u ? *hint_u : -1.0);
  const double u = a / radius_m;
  if (hint_u) *hint_u = u;
  // F = E* R^2 [(1 + u^2) atanh(u) - u]; a series below u = 0.01 avoids the cancellation.
  double shape;
  if (u < 1e-2) {
    const double u2 = u * u;
    shape = u * u2 * (4.0 / 3.0 + u2 * (8.0 / 15.0 + u2 * (12.0 / 35.0)));
  } else {
    shape = (1.0 + u * u) * atanh_unit(u) - u;
  }
  return {e_star_Pa * radius_m * radius_m * shape, 2.0 * e_star_Pa * a};
}

double bottom_effect_factor(double chi) {
  return 1.0 + chi * (1.133 + chi * (1.283 + chi * (0.769 + chi * 0.0975)));
}

double bottom_effect_factor_slope(double chi) {
  return 1.133 + chi * (2.566 + chi * (2.307 + chi * 0.39));
}

ElasticPoint sphere_on_layer(const ContactParams& params, double radius_m, double depth_m) {
  if (!(depth_m > 0.0)) return {};
  ElasticPoint p = params.law == ContactLaw::hertz
                       ? hertz_sphere(params.e_star_Pa, radius_m, depth_m)
                       : sneddon_sphere_tabulated(params.e_star_Pa, radius_m, depth_m);
  const double h = params.layer_thickness_m;
  if (h > 0.0) {
    const double chi = std::sqrt(radius_m * depth_m) / h;
    const double phi = bottom_effect_factor(chi);
    const double dchi = chi / (2.0 * depth_m);
    p.stiffness_N_per_m =
        p.stiffness_N_per_m * phi + p.force_N * bottom_effect_factor_slope(chi) * dchi;
    p.force_N *= phi;
  }
  return p;
}

ElasticPoint elastic_contact(const ContactParams& params, double radius_m, double depth_m,
                             double* hint_contact_depth) {
  if (!(depth_m > 0.0)) {
    if (hint_contact_depth) *hint_contact_depth = 0.0;
    return {};
  }
  const double c = params.structural_compliance_m_per_N;
  if (!(c > 0.0)) {
    if (hint_contact_depth) *hint_contact_depth = depth_m;
    return sphere_on_layer(params, radius_m, depth_m);
  }
  // g(x) = x + c F(x) - delta: increasing and convex, so Newton converges from any start in
  // [0, delta] (a start left of the root jumps right of it, then descends monotonically).
  double x = depth_m;
  if (hint_contact_depth && *hint_contact_depth > 0.0) x = std::min(*hint_contact_depth, depth_m);
  // A step below kLastStep delta is the last: taken along the tangent (force F - k dx), it leaves
  // the force within F'' dx^2 / 2 (relative ~1e-16) of the law's at the new x and the tangent
  // within k' dx (relative below kLastStep / 2 for a sphere, k ~ sqrt(delta)) of it, one
  // evaluation sooner than stepping on until a step vanishes.
  constexpr double kLastStep = 1e-8;
  ElasticPoint p{};
  for (int iter = 0; iter < 100; ++iter) {
    p = sphere_on_layer(params, radius_m, x);
    const double g = x + c * p.force_N - depth_m;
    const double dx = g / (1.0 + c * p.stiffness_N_per_m);
    if (std::abs(dx) <= kLastStep * depth_m) {
      p.force_N -= p.stiffness_N_per_m * dx;
      x = std::clamp(x - dx, 0.0, depth_m);
      break;
    }
    x = std::clamp(x - dx, 0.0, depth_m);
  }
  if (hint_contact_depth) *hint_contact_depth = x;
  return {p.force_N, p.stiffness_N_per_m / (1.0 + c * p.stiffness_N_per_m)};
}

}  // namespace palp::plant
