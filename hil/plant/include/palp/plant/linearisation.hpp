// SPDX-License-Identifier: Apache-2.0
// Small-signal linearisation of the plant about its static equilibrium at a bias current
// (README.md "Equations"): the reference the dynamic identification (issue 7) is judged by.
//
// Static equilibrium at bias i_0, the stroke s_0 where the forces balance (probe vertical):
//   K_f(s_0) i_0 - k_v (s_0 - s_n) + m_v g cos(theta) - F_el(delta_0) = 0,
//   delta_0 = z_mount + s_0 - z_touch      (F_el = 0 while delta_0 <= 0: free air),
// with s_n the springs' neutral point and F_el the relaxed elastic contact law at the mount's
// site (sphere on its layer, thickness factor, structural compliance in series).
// About it, force F = K_f(s_0) i in, stroke s out, G(s) = 1 / (m s^2 + b s + k) with
//   k = k_v + k_o - i_0 dK_f/ds(s_0)    k_o = dF_el/d(delta) at delta_0 (the law's tangent;
//                                       the last term is the coil's hidden spring, 0 where the
//                                       K_f table is flat, i.e. over the working range)
//   m = m_v + m_o(delta_0)              participating mass engaged at delta_0
//   b = b_v + tau k_o                   Kelvin-Voigt (retardation time tau)
// and omega_n = sqrt(k / m), zeta = b / (2 sqrt(k m)).
//
// A standard linear solid (strength g_1, relaxation time tau_1) adds to the contact the
// frequency-dependent stiffness k_r j w tau_1 / (1 + j w tau_1), k_r = g_1 k_o (its extra force q
// relaxes toward 0 while following g_1 dF_el/dt): the static equilibrium is the relaxed law's, G
// below is exact, and k, b, omega_n, zeta are the second order that matches the dynamic
// stiffness at its own natural frequency (solved by fixed point):
//   k = k_v + k_o + k_r w^2 tau_1^2 / (1 + w^2 tau_1^2) - i_0 dK_f/ds,
//   b = b_v + tau k_o + k_r tau_1 / (1 + w^2 tau_1^2),    w = omega_n = sqrt(k / m).
// A fit of a second order over a band around the resonance finds it when w tau_1 >> 1 there
// (the relaxing part then barely varies across the band; the pad: hil/plant/README.md).
#pragma once

#include <complex>

#include "palp/plant/plant.hpp"

namespace palp::plant {

struct Linearisation {
  double bias_A = 0.0;
  bool in_contact = false;           ///< delta_0 > 0
  double stroke_m = 0.0;             ///< s_0, from the stroke origin
  double depth_m = 0.0;              ///< delta_0 (0 in free air)
  double contact_force_N = 0.0;      ///< F_el(delta_0), relaxed
  double kf_N_per_A = 0.0;           ///< K_f(s_0)
  double k_v_N_per_m = 0.0, k_o_N_per_m = 0.0, k_coil_N_per_m = 0.0, k_N_per_m = 0.0;
  double m_v_kg = 0.0, m_o_kg = 0.0, m_kg = 0.0;
  double b_v_N_s_per_m = 0.0, b_o_N_s_per_m = 0.0, b_N_s_per_m = 0.0;
  /// Standard linear solid (0 for Kelvin-Voigt): k_r = g_1 k_o and tau_1, and the stiffness and
  /// damping the relaxing part adds at omega_n (included in k_N_per_m and b_N_s_per_m).
  double k_relaxing_N_per_m = 0.0, relaxation_time_s = 0.0;
  double k_sls_N_per_m = 0.0, b_sls_N_s_per_m = 0.0;
  double omega_n_rad_per_s = 0.0, zeta = 0.0;
  /// The linear model's response Z/F at f_Hz, m/N (x = Re{X e^{jwt}}: Im G <= 0).
  std::complex<double> G(double f_Hz) const;
};

/// Linearise `plant` at bias_A with its mount where it is now (the current site and height;
/// the coil's own state is irrelevant). Throws std::domain_error naming the stop when the
/// equilibrium lies on an end stop (no small-signal dynamics there) and std::invalid_argument
/// for a non-finite bias.
Linearisation linearise(const Plant& plant, double bias_A);

/// Free air (no phantom): k = k_v (+ the coil's hidden spring), m = m_v, b = b_v.
Linearisation linearise_free_air(const PlantConfig& config, double bias_A);

}  // namespace palp::plant
