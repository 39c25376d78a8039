// SPDX-License-Identifier: Apache-2.0
// LinePhantom: the 1D objects, per-position contact laws interpolated along x.
#include "palp/plant/line_phantom.hpp"

#include <cmath>
#include <limits>

namespace palp::plant {
namespace {

double inverse_or_zero(double h) { return h > 0.0 ? 1.0 / h : 0.0; }

}  // namespace

LinePhantom::LinePhantom(LinePhantomSpec spec)
    : Phantom(spec, PhantomKind::line_1d), spec_(std::move(spec)) {
  const std::size_t n = spec_.e_star_Pa.size();
  if (n == 0 || spec_.layer_thickness_m.size() != n ||
      spec_.structural_compliance_m_per_N.size() != n || spec_.participating_mass_kg.size() != n ||
      spec_.retardation_time_s.size() != n) {
    throw PhantomError(name() + ": per-position tables must be non-empty and equally long");
  }
  if (!(spec_.position_pitch_m > 0.0) || !(spec_.length_m > 0.0) || !(spec_.width_m > 0.0)) {
    throw PhantomError(name() + ": length, width and pitch must be positive");
  }
}

double LinePhantom::surface_z_m(double x_m, double y_m) const {
  if (x_m < 0.0 || x_m > spec_.length_m || std::abs(y_m) > 0.5 * spec_.width_m) {
    return std::numeric_limits<double>::infinity();
  }
  return spec_.surface_z_m;
}

ContactParams LinePhantom::contact_params(double x_m, double /*y_m*/) const {
  const std::size_t n = spec_.e_star_Pa.size();
  const double t = (x_m - spec_.first_position_x_m) / spec_.position_pitch_m;
  std::size_t k0 = 0;
  double w = 0.0;
  if (t >= static_cast<double>(n - 1)) {
    k0 = n - 1;
  } else if (t > 0.0) {
    k0 = static_cast<std::size_t>(t);
    w = t - static_cast<double>(k0);
  }
  const std::size_t k1 = std::min(k0 + 1, n - 1);
  auto blend = [&](const std::vector<double>& v) { return (1.0 - w) * v[k0] + w * v[k1]; };

  ContactParams p;
  p.law = spec_.law;
  p.viscoelasticity = spec_.viscoelasticity;
  p.sls_relaxation_time_s = spec_.sls_relaxation_time_s;
  p.sls_strength = spec_.sls_strength;
  p.mass_engage_depth_m = spec_.mass_engage_depth_m;
  p.e_star_Pa = blend(spec_.e_star_Pa);
  const double inv_h = (1.0 - w) * inverse_or_zero(spec_.layer_thickness_m[k0]) +
                       w * inverse_or_zero(spec_.layer_thickness_m[k1]);
  p.layer_thickness_m = inverse_or_zero(inv_h);
  p.structural_compliance_m_per_N = blend(spec_.structural_compliance_m_per_N);
  p.participating_mass_kg = blend(spec_.participating_mass_kg);
  p.retardation_time_s = blend(spec_.retardation_time_s);
  return p;
}

std::vector<ProbeSite> LinePhantom::sites() const {
  std::vector<ProbeSite> out;
  const std::size_t n = spec_.e_star_Pa.size();
  for (std::size_t k = 0; k < n; ++k) {
    out.push_back({0, static_cast<int>(k + 1),
                   spec_.first_position_x_m + static_cast<double>(k) * spec_.position_pitch_m,
                   0.0});
  }
  return out;
}

}  // namespace palp::plant
