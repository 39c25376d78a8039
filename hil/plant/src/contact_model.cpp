// SPDX-License-Identifier: Apache-2.0
// ContactModel: the per-step contact force (elastic + Kelvin-Voigt + optional relaxation).
#include <algorithm>
#include <cmath>

#include "palp/plant/contact.hpp"

namespace palp::plant {

void ContactModel::reset() {
  q_N_ = 0.0;
  last_elastic_N_ = 0.0;
  hint_depth_ = 0.0;
  last_depth_m_ = 0.0;
  last_stiffness_N_per_m_ = 0.0;
}

ContactModel::Output ContactModel::evaluate(const ContactParams& params, double radius_m,
                                            double depth_m, double depth_rate_m_per_s,
                                            double dt_s, double cos_theta) {
  if (cos_theta == 1.0) return evaluate_normal(params, radius_m, depth_m, depth_rate_m_per_s, dt_s);
  // Oblique axis: the law runs on the normal approach (a Kelvin-Voigt or SLS solid scales its
  // moduli, not nu, so Mindlin's split holds for the rate terms too: one factor for all).
  const ObliqueSplit split = oblique_split(cos_theta, params.friction_coefficient);
  Output out = evaluate_normal(params, radius_m, depth_m * split.cos_theta,
                               depth_rate_m_per_s * split.cos_theta, dt_s);
  const double g = split.axial_per_normal;  // axial force per normal force
  const double gc = g * split.cos_theta;    // axial stiffness per normal stiffness
  out.force_N *= g;
  out.elastic_force_N *= g;
  out.rate_free_force_N *= g;
  out.stiffness_N_per_m *= gc;
  out.damping_N_s_per_m *= gc;
  out.axial_per_normal = g;
  out.tangential_per_normal = split.tangential_per_normal;
  return out;
}

ContactModel::Output ContactModel::evaluate_normal(const ContactParams& params, double radius_m,
                                                   double depth_m, double depth_rate_m_per_s,
                                                   double dt_s) {
  Output out;
  const bool touching = depth_m > 0.0;
  if (touching) {
    // the series solve starts from last step's answer moved along its tangent:
    // d(delta_c)/d(delta) = 1 / (1 + c_s k) = 1 - c_s k_t (one Newton step, for free)
    if (hint_depth_ > 0.0) {
      hint_depth_ += (depth_m - last_depth_m_) *
                     (1.0 - params.structural_compliance_m_per_N * last_stiffness_N_per_m_);
    }
    const ElasticPoint el = elastic_contact(params, radius_m, depth_m, &hint_depth_);
    last_depth_m_ = depth_m;
    last_stiffness_N_per_m_ = el.stiffness_N_per_m;
    out.elastic_force_N = el.force_N;
    out.stiffness_N_per_m = el.stiffness_N_per_m;
  } else {
    hint_depth_ = 0.0;
  }

  // Standard linear solid (quasi-linear form), exact for F_el changing linearly over the step.
  const double tau1 = params.sls_relaxation_time_s;
  if (params.viscoelasticity == Viscoelasticity::standard_linear_solid && tau1 > 0.0 &&
      params.sls_strength > 0.0) {
    if (dt_s != cached_dt_ || tau1 != cached_tau_) {
      cached_dt_ = dt_s;
      cached_tau_ = tau1;
      decay_ = dt_s > 0.0 ? std::exp(-dt_s / tau1) : 1.0;
      gain_ = dt_s > 0.0 ? tau1 / dt_s * (1.0 - decay_) : 1.0;
    }
    q_N_ = q_N_ * decay_ + params.sls_strength * (out.elastic_force_N - last_elastic_N_) * gain_;
  } else {
    q_N_ = 0.0;
  }
  last_elastic_N_ = out.elastic_force_N;

  if (touching) {
    out.touching = true;
    out.rate_free_force_N = out.elastic_force_N + q_N_;
    out.damping_N_s_per_m = params.retardation_time_s * out.stiffness_N_per_m;
    out.force_N = std::max(0.0, out.rate_free_force_N + out.damping_N_s_per_m * depth_rate_m_per_s);
    const double engage = params.mass_engage_depth_m > 0.0
                              ? std::min(1.0, depth_m / params.mass_engage_depth_m)
                              : 1.0;
    out.mass_kg = params.participating_mass_kg * engage;
  }
  return out;
}

}  // namespace palp::plant
