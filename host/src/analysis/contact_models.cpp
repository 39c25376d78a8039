// SPDX-License-Identifier: Apache-2.0
// Contact laws: see palp/analysis/contact_models.hpp.
#include "palp/analysis/contact_models.hpp"

#include <algorithm>
#include <cmath>

namespace palp::analysis {

namespace {

// (1 + t^2) atanh(t) - t without cancellation for small t = a/R:
// the series sum over k >= 1 of 4k / (4k^2 - 1) t^(2k+1).
double sneddon_shape(double t) {
  if (t < 0.2) {
    double sum = 0.0;
    const double t2 = t * t;
    double power = t * t2;
    for (int k = 1; k < 40; ++k) {
      const double term = 4.0 * k / (4.0 * k * k - 1.0) * power;
      sum += term;
      if (term < 1e-18 * sum) break;
      power *= t2;
    }
    return sum;
  }
  return (1.0 + t * t) * std::atanh(t) - t;
}

const double kBonded[4] = {1.133, 1.283, 0.769, 0.0975};
const double kUnbonded[4] = {0.884, 0.781, 0.386, 0.0048};

// u = atanh(a/R) solving u tanh(u) = delta/R (increasing in u; bracketed below by
// max(sqrt(target), target) and above as commented). Safeguarded Newton. Working in u keeps
// full precision as a -> R, where a/R itself rounds to 1.
double sneddon_u(double target) {
  double lo = target < 1.0 ? std::sqrt(target) * 0.99 : target;
  double hi = target + 1.0;
  // u tanh(u) >= tanh(1) u^2 for u <= 1 and >= tanh(1) u for u >= 1.
  constexpr double tanh1 = 0.76159415595576489;
  hi = std::min(hi, std::max(std::sqrt(target / tanh1), target / tanh1) * 1.01);
  lo = std::min(lo, hi);
  // start: u tanh u = u^2 - u^4/3 + ... inverted, u^2 ~ t + t^2/3 for small t
  double u = target < 1.0 ? std::sqrt(target * (1.0 + target / 3.0)) : target + 0.5;
  u = std::clamp(u, lo, hi);
  for (int it = 0; it < 100; ++it) {
    const double th = std::tanh(u);
    const double g = u * th - target;
    if (g == 0.0) break;
    if (g > 0.0) hi = u; else lo = u;
    const double dg = th + u * (1.0 - th * th);
    double next = u - g / dg;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // a Newton step below 1e-9 u leaves an error of order its square: full precision (waiting
    // for a zero step instead can bounce between neighbouring doubles for dozens of steps)
    if (std::abs(next - u) <= 1e-9 * u) { u = next; break; }
    u = next;
  }
  return u;
}

}  // namespace

double hertz_force_N(double depth_m, double Estar_Pa, double radius_m) {
  if (!(depth_m > 0.0)) return 0.0;
  return 4.0 / 3.0 * Estar_Pa * std::sqrt(radius_m) * depth_m * std::sqrt(depth_m);
}

double hertz_stiffness_N_per_m(double depth_m, double Estar_Pa, double radius_m) {
  if (!(depth_m > 0.0)) return 0.0;
  return 2.0 * Estar_Pa * std::sqrt(radius_m * depth_m);
}

double sneddon_contact_radius_m(double depth_m, double radius_m) {
  if (!(depth_m > 0.0)) return 0.0;
  return radius_m * std::tanh(sneddon_u(depth_m / radius_m));
}

double sneddon_force_N(double depth_m, double Estar_Pa, double radius_m) {
  if (!(depth_m > 0.0)) return 0.0;
  const double u = sneddon_u(depth_m / radius_m);
  const double t = std::tanh(u);
  const double shape = t < 0.2 ? sneddon_shape(t) : (1.0 + t * t) * u - t;
  return Estar_Pa * radius_m * radius_m * shape;
}

double sneddon_stiffness_N_per_m(double depth_m, double Estar_Pa, double radius_m) {
  return 2.0 * Estar_Pa * sneddon_contact_radius_m(depth_m, radius_m);
}

ForceStiffness sneddon_force_stiffness(double depth_m, double Estar_Pa, double radius_m) {
  if (!(depth_m > 0.0)) return {0.0, 0.0};
  const double u = sneddon_u(depth_m / radius_m);
  const double t = std::tanh(u);
  const double shape = t < 0.2 ? sneddon_shape(t) : (1.0 + t * t) * u - t;
  return {Estar_Pa * radius_m * radius_m * shape, 2.0 * Estar_Pa * radius_m * t};
}

double thickness_factor(double depth_m, double radius_m, const Thickness& t) {
  if (!(depth_m > 0.0)) return 1.0;
  const double* c = t.bonding == Bonding::bonded ? kBonded : kUnbonded;
  const double chi = std::sqrt(radius_m * depth_m) / t.thickness_m;
  return 1.0 + chi * (c[0] + chi * (c[1] + chi * (c[2] + chi * c[3])));
}

double thickness_factor_derivative_per_m(double depth_m, double radius_m, const Thickness& t) {
  if (!(depth_m > 0.0)) return 0.0;
  const double* c = t.bonding == Bonding::bonded ? kBonded : kUnbonded;
  const double chi = std::sqrt(radius_m * depth_m) / t.thickness_m;
  const double dfactor_dchi = c[0] + chi * (2.0 * c[1] + chi * (3.0 * c[2] + chi * 4.0 * c[3]));
  return dfactor_dchi * chi / (2.0 * depth_m);  // dchi/ddelta = chi / (2 delta)
}

double effective_modulus_Pa(double E_Pa, double poisson) { return E_Pa / (1.0 - poisson * poisson); }
double youngs_modulus_Pa(double Estar_Pa, double poisson) { return Estar_Pa * (1.0 - poisson * poisson); }

}  // namespace palp::analysis
