// SPDX-License-Identifier: Apache-2.0
// Small-signal linearisation about the static equilibrium at a bias current.
#include "palp/plant/linearisation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace palp::plant {
namespace {

struct Site {
  bool touches = false;
  double gap_offset_m = 0.0;  // delta = s + gap_offset, along the probe's axis
  double cos_theta = 1.0;     // the axis against the surface normal (README.md "Oblique contact")
};

// Net force on the coil at rest at stroke s (positive toward +z), with the relaxed contact law.
double net_force(const Plant& plant, const Site& site, double bias_A, double s) {
  const MechanicsConfig& m = plant.config().mechanics;
  double f = plant.force_constant().at(s) * bias_A -
             m.spring_rate_N_per_m * (s - plant.spring_neutral_m()) +
             m.moving_mass_kg * m.gravity_m_per_s2 * m.gravity_axis_cosine;
  if (site.touches) {
    f -= oblique_elastic_contact(plant.contact_params(), m.tip_radius_m, s + site.gap_offset_m,
                                 site.cos_theta)
             .force_N;
  }
  return f;
}

}  // namespace

std::complex<double> Linearisation::G(double f_Hz) const {
  const double w = 2.0 * std::numbers::pi * f_Hz;
  if (k_relaxing_N_per_m > 0.0) {  // the exact dynamic stiffness: without the equivalents
    const std::complex<double> jwt(0.0, w * relaxation_time_s);
    const std::complex<double> d =
        std::complex<double>(k_N_per_m - k_sls_N_per_m - m_kg * w * w,
                             (b_N_s_per_m - b_sls_N_s_per_m) * w) +
        k_relaxing_N_per_m * jwt / (1.0 + jwt);
    return 1.0 / d;
  }
  return 1.0 / std::complex<double>(k_N_per_m - m_kg * w * w, b_N_s_per_m * w);
}

Linearisation linearise(const Plant& plant, double bias_A) {
  if (!std::isfinite(bias_A)) throw std::invalid_argument("linearise: bias current is not finite");
  const MechanicsConfig& m = plant.config().mechanics;
  const SphereTouch touch = plant.site_touch();
  Site site;
  if (plant.phantom() && touch.touches && std::isfinite(touch.apex_z_m)) {
    site.touches = true;
    const double axis_z = plant.probe_axis()[2];
    site.gap_offset_m =
        ((plant.tip_z_m() - plant.position_m() * axis_z) - touch.apex_z_m) / axis_z;
    site.cos_theta = plant.axis_normal_cosine();
  }

  // The net force falls with s (springs, contact; K_f's slope times the current stays below
  // k_v for currents up to ~1.4 A on the default table): bisection for its zero.
  double lo = m.stroke_min_m, hi = m.stroke_max_m;
  if (net_force(plant, site, bias_A, lo) <= 0.0) {
    throw std::domain_error("linearise: at " + std::to_string(bias_A) +
                            " A the coil rests on the rear end stop");
  }
  if (net_force(plant, site, bias_A, hi) >= 0.0) {
    throw std::domain_error("linearise: at " + std::to_string(bias_A) +
                            " A the coil rests on the front end stop");
  }
  for (int iter = 0; iter < 200 && hi - lo > 1e-15; ++iter) {
    const double mid = 0.5 * (lo + hi);
    (net_force(plant, site, bias_A, mid) > 0.0 ? lo : hi) = mid;
  }
  const double s0 = 0.5 * (lo + hi);

  Linearisation r;
  r.bias_A = bias_A;
  r.stroke_m = s0;
  r.kf_N_per_A = plant.force_constant().at(s0);
  r.k_v_N_per_m = m.spring_rate_N_per_m;
  r.k_coil_N_per_m = -bias_A * plant.force_constant().slope(s0);
  r.m_v_kg = m.moving_mass_kg;
  r.b_v_N_s_per_m = m.damping_N_s_per_m;
  const double depth = s0 + site.gap_offset_m;
  if (site.touches && depth > 0.0) {
    const ContactParams& p = plant.contact_params();
    const ElasticPoint el = oblique_elastic_contact(p, m.tip_radius_m, depth, site.cos_theta);
    r.in_contact = true;
    r.depth_m = depth;
    r.contact_force_N = el.force_N;
    r.k_o_N_per_m = el.stiffness_N_per_m;
    r.b_o_N_s_per_m = p.retardation_time_s * el.stiffness_N_per_m;
    const double normal_depth = depth * site.cos_theta;
    const double engage =
        p.mass_engage_depth_m > 0.0 ? std::min(1.0, normal_depth / p.mass_engage_depth_m) : 1.0;
    r.m_o_kg = p.participating_mass_kg * engage;
    if (p.viscoelasticity == Viscoelasticity::standard_linear_solid &&
        p.sls_relaxation_time_s > 0.0 && p.sls_strength > 0.0) {
      r.k_relaxing_N_per_m = p.sls_strength * el.stiffness_N_per_m;
      r.relaxation_time_s = p.sls_relaxation_time_s;
    }
  }
  r.m_kg = r.m_v_kg + r.m_o_kg;
  const double k_static = r.k_v_N_per_m + r.k_o_N_per_m + r.k_coil_N_per_m;
  const double b_static = r.b_v_N_s_per_m + r.b_o_N_s_per_m;
  // the standard linear solid's equivalents at omega_n: a contraction (k_sls grows slowly with w)
  double w = std::sqrt((k_static + r.k_relaxing_N_per_m) / r.m_kg);
  for (int iter = 0; iter < 100 && r.k_relaxing_N_per_m > 0.0; ++iter) {
    const double wt2 = w * w * r.relaxation_time_s * r.relaxation_time_s;
    r.k_sls_N_per_m = r.k_relaxing_N_per_m * wt2 / (1.0 + wt2);
    r.b_sls_N_s_per_m = r.k_relaxing_N_per_m * r.relaxation_time_s / (1.0 + wt2);
    const double next = std::sqrt((k_static + r.k_sls_N_per_m) / r.m_kg);
    if (std::abs(next - w) <= 1e-14 * w) break;
    w = next;
  }
  r.k_N_per_m = k_static + r.k_sls_N_per_m;
  r.b_N_s_per_m = b_static + r.b_sls_N_s_per_m;
  r.omega_n_rad_per_s = std::sqrt(r.k_N_per_m / r.m_kg);
  r.zeta = r.b_N_s_per_m / (2.0 * std::sqrt(r.k_N_per_m * r.m_kg));
  return r;
}

Linearisation linearise_free_air(const PlantConfig& config, double bias_A) {
  return linearise(Plant(config, nullptr), bias_A);
}

}  // namespace palp::plant
