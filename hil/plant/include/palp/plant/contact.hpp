// SPDX-License-Identifier: Apache-2.0
// Contact of the spherical tip with a phantom (README.md "Contact"):
//
//   elastic part   sphere on a bonded layer (Hertz or exact Sneddon sphere, tabulated, times the
//                  Dimitriadis finite-thickness factor), in series with a linear structural
//                  spring (a void or a channel under the site): depth delta = delta_c + c_s F;
//   viscous part   Kelvin-Voigt with retardation time tau: F_v = tau * k_t(delta) * d(delta)/dt
//                  (exact for a Kelvin-Voigt solid by the correspondence principle);
//   relaxation     optional standard linear solid (quasi-linear viscoelastic form): an extra
//                  force q with dq/dt = -q/tau_1 + g_1 dF_el/dt, so the relaxed law is F_el;
//   inertia        a participating material mass that engages over the first millimetre;
//   oblique axis   the probe's axis at theta to the surface normal (README.md "Oblique
//                  contact"): the law at the normal approach delta cos(theta), plus Mindlin's
//                  tangential force under full stick, limited by Coulomb friction.
// All functions are pure except ContactModel, which carries the relaxation memory and warm starts.
#pragma once

#include <array>
#include <cstddef>

namespace palp::plant {

inline constexpr std::size_t kPressureChannels = 6;

enum class ContactLaw { hertz, sneddon };
enum class Viscoelasticity { kelvin_voigt, standard_linear_solid };

/// The contact law at one site of a phantom (Phantom::contact_params).
struct ContactParams {
  ContactLaw law = ContactLaw::hertz;
  double e_star_Pa = 0.0;                      // effective modulus E/(1 - nu^2), relaxed
  double layer_thickness_m = 0.0;              // bonded layer for the bottom effect; 0 = half-space
  double structural_compliance_m_per_N = 0.0;  // series structural spring 1/k_s; 0 = none
  double retardation_time_s = 0.0;             // Kelvin-Voigt tau: damping = tau * k_tangent
  Viscoelasticity viscoelasticity = Viscoelasticity::kelvin_voigt;
  double sls_relaxation_time_s = 0.0;  // standard linear solid: tau_1
  double sls_strength = 0.0;           // g_1 = instantaneous / relaxed stiffness - 1
  double participating_mass_kg = 0.0;  // material mass moving with the tip in contact
  double mass_engage_depth_m = 1e-3;   // depth over which that mass engages linearly
  double friction_coefficient = 0.5;   // tip on material, Coulomb (phantom key; README.md)
  // Pad only: volume squeezed out of each channel per newton of contact force, m^3/N
  // (index 0 = paper channel 1).
  std::array<double, kPressureChannels> channel_gain_m3_per_N{};
};

/// Elastic force and tangent stiffness at one depth.
struct ElasticPoint {
  double force_N = 0.0;
  double stiffness_N_per_m = 0.0;  // dF/d(delta), the tangent stiffness
};

/// Hertz sphere (paraboloid) on a half-space: F = 4/3 E* sqrt(R) delta^1.5.
ElasticPoint hertz_sphere(double e_star_Pa, double radius_m, double depth_m);

/// Contact radius a of the exact Sneddon sphere at depth delta: delta = (a/2) ln((R+a)/(R-a)).
/// Newton on u = a/R from hint_u if it is in (0, 1), else from a safe bound.
double sneddon_contact_radius(double radius_m, double depth_m, double hint_u = -1.0);

/// Exact Sneddon sphere on a half-space: F = E* [ (R^2 + a^2)/2 ln((R+a)/(R-a)) - a R ],
/// dF/d(delta) = 2 E* a. hint_u: optional warm start (a/R), updated to the solution.
ElasticPoint sneddon_sphere(double e_star_Pa, double radius_m, double depth_m,
                            double* hint_u = nullptr);

/// The Sneddon sphere as the plant evaluates it, from a table of the law's smooth factors (512
/// cubic cells over depth / radius in [0, kSneddonTableMaxDepth], README.md "Speed and
/// sameness"): force and stiffness within kSneddonTableError relative of sneddon_sphere(), for
/// a few tens of instructions instead of two Newton solves; deeper than the table, sneddon_sphere().
inline constexpr double kSneddonTableMaxDepth = 4.0;  ///< depth / radius (10 mm at R = 2.5 mm)
inline constexpr double kSneddonTableError = 1e-11;   ///< relative, force and stiffness
ElasticPoint sneddon_sphere_tabulated(double e_star_Pa, double radius_m, double depth_m);

/// Dimitriadis et al. (2002) bonded-layer factor for nu = 0.5, chi = sqrt(R delta)/h:
/// 1 + 1.133 chi + 1.283 chi^2 + 0.769 chi^3 + 0.0975 chi^4 (and its derivative).
double bottom_effect_factor(double chi);
double bottom_effect_factor_slope(double chi);

/// The sphere law of `params` (without the series spring) at contact depth delta_c (Sneddon:
/// sneddon_sphere_tabulated).
ElasticPoint sphere_on_layer(const ContactParams& params, double radius_m, double depth_m);

/// The whole elastic (relaxed) law at total depth delta, series spring included: solves
/// delta_c + c_s F(delta_c) = delta by Newton from hint_contact_depth (updated).
ElasticPoint elastic_contact(const ContactParams& params, double radius_m, double depth_m,
                             double* hint_contact_depth = nullptr);

/// Poisson's ratio of every phantom material: incompressible elastomer (as the Dimitriadis
/// factor assumes).
inline constexpr double kPoissonRatio = 0.5;

/// Mindlin (1949) / Johnson, Contact Mechanics (1985) §7.2: the tangential stiffness 8 G* a of
/// a circular contact under full stick over the normal one 2 E* a, for a rigid tip on a
/// material of Poisson's ratio nu: 2 (1 - nu) / (2 - nu) (2/3 at nu = 0.5).
double mindlin_stiffness_ratio(double poisson_ratio);

/// How the forces of a contact split when the probe's axis is at theta to the surface normal
/// (Johnson 1985 §7.5, oblique loading at a constant ratio): the tip's displacement delta along
/// the axis is a normal approach delta cos(theta) and a tangential one delta sin(theta); the
/// tangential force is rho tan(theta) F_n (rho: mindlin_stiffness_ratio) while that stays below
/// mu F_n (no slip anywhere), else mu F_n (the whole contact slides).
struct ObliqueSplit {
  double cos_theta = 1.0;              ///< axis . normal: normal approach per axial depth
  double sin_theta = 0.0;
  double tangential_per_normal = 0.0;  ///< F_t / F_n = min(rho tan(theta), mu)
  double axial_per_normal = 1.0;       ///< F_axis / F_n = cos(theta) + (F_t/F_n) sin(theta)
  double lateral_per_normal = 0.0;     ///< across the axis, F_lat / F_n = sin - (F_t/F_n) cos
  bool sliding = false;                ///< rho tan(theta) > mu
};

/// The split for cos(theta) in (0, 1] and friction coefficient mu >= 0 (cos_theta = 1 gives
/// exactly cos 1, sin 0, axial 1, tangential 0).
ObliqueSplit oblique_split(double cos_theta, double friction_coefficient);

/// The relaxed law along an axis at theta to the normal, at axial depth delta:
///   F_axis(delta) = F_n(delta cos theta) (cos theta + (F_t/F_n) sin theta),
///   k_axis = dF_axis/d(delta) = k_n(delta cos theta) cos theta (cos theta + (F_t/F_n) sin theta)
/// (= k_n (cos^2 theta + rho sin^2 theta) under full stick). cos_theta = 1: elastic_contact.
ElasticPoint oblique_elastic_contact(const ContactParams& params, double radius_m,
                                     double axial_depth_m, double cos_theta);

/// Per-step contact state: relaxation memory and warm starts. evaluate() is called once per
/// step; it never allocates.
class ContactModel {
 public:
  struct Output {
    double force_N = 0.0;            // total force on the tip (>= 0), against the probe's axis
    double elastic_force_N = 0.0;    // relaxed elastic part F_el
    double stiffness_N_per_m = 0.0;  // tangent of F_el
    double rate_free_force_N = 0.0;  // F_el + q: the force at zero indentation rate (unclamped)
    double damping_N_s_per_m = 0.0;  // Kelvin-Voigt coefficient tau * k_t (0 out of contact)
    double mass_kg = 0.0;            // participating material mass engaged now
    bool touching = false;           // depth > 0
    // The oblique split used (ObliqueSplit): force_N, elastic_force_N, stiffness_N_per_m,
    // rate_free_force_N and damping_N_s_per_m are along the probe's axis; the normal force is
    // force_N / axial_per_normal, the tangential one that times tangential_per_normal.
    double axial_per_normal = 1.0;
    double tangential_per_normal = 0.0;
  };

  /// Forget the history (a fresh, relaxed, unloaded contact).
  void reset();

  /// Force at depth delta (<= 0: no contact) moving at delta_rate, advancing the relaxation
  /// memory by dt_s since the previous call (dt_s = 0: an instantaneous change of depth).
  /// force_N = max(0, rate_free_force_N + damping_N_s_per_m * delta_rate) when touching.
  /// Oblique axis (cos_theta < 1: the axis at theta to the normal): depth and rate are along
  /// the axis; the law (memory included) runs on the normal approach depth cos(theta) and every
  /// force and coefficient is returned along the axis (oblique_split). cos_theta = 1 is the
  /// normal law bit for bit.
  Output evaluate(const ContactParams& params, double radius_m, double depth_m,
                  double depth_rate_m_per_s, double dt_s, double cos_theta = 1.0);

  double relaxation_force_N() const { return q_N_; }

 private:
  Output evaluate_normal(const ContactParams& params, double radius_m, double depth_m,
                         double depth_rate_m_per_s, double dt_s);

  double q_N_ = 0.0;             // standard-linear-solid extra force
  double last_elastic_N_ = 0.0;  // F_el at the previous call
  double hint_depth_ = 0.0;      // warm start of the series solve (its last contact depth)
  double last_depth_m_ = 0.0, last_stiffness_N_per_m_ = 0.0;  // its last depth and tangent
  double cached_dt_ = -1.0, cached_tau_ = -1.0, decay_ = 0.0, gain_ = 0.0;
};

}  // namespace palp::plant
