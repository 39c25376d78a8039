// SPDX-License-Identifier: Apache-2.0
// Contact laws for a rigid spherical tip on an elastic half-space, in SI (m, N, Pa).
//
// Depth delta = z - z_c >= 0 below the contact point; E* = E / (1 - nu^2) (rigid tip).
// Formulas and checks: shared/reference/analysis-notes.md, "Quasi-static curves".
//   Hertz paraboloid:  F = 4/3 E* sqrt(R) delta^(3/2),       dF/ddelta = 2 E* sqrt(R delta)
//   Sneddon sphere:    delta = (a/2) ln((R+a)/(R-a)) = a atanh(a/R),
//                      F = E* [ (R^2+a^2)/2 ln((R+a)/(R-a)) - a R ], dF/ddelta = 2 E* a
//                      (a < R; solved by safeguarded Newton in u = atanh(a/R), so the force
//                      keeps full precision at large depth; a rounds to R past delta/R ~ 18)
//   Finite thickness h (Dimitriadis 2002), chi = sqrt(R delta)/h:
//                      F = F_model * (1 + c1 chi + c2 chi^2 + c3 chi^3 + c4 chi^4)
// Negative depths are out of contact: every function returns 0 there.
#pragma once

#include <optional>

namespace palp::analysis {

/// How the sample sits on its support, for the finite-thickness correction.
enum class Bonding { bonded, unbonded };

/// Sample thickness for the bottom-effect correction; absent = semi-infinite half-space.
struct Thickness {
  double thickness_m = 0.0;
  Bonding bonding = Bonding::bonded;
};

double hertz_force_N(double depth_m, double Estar_Pa, double radius_m);
/// dF/ddelta of the Hertz law (0 at and below contact).
double hertz_stiffness_N_per_m(double depth_m, double Estar_Pa, double radius_m);

/// Contact radius a in [0, R) of the exact sphere at this depth (0 for depth <= 0).
double sneddon_contact_radius_m(double depth_m, double radius_m);
double sneddon_force_N(double depth_m, double Estar_Pa, double radius_m);
/// dF/ddelta of the exact sphere: 2 E* a(delta).
double sneddon_stiffness_N_per_m(double depth_m, double Estar_Pa, double radius_m);
/// Both from one solve for a(delta) (what a fit's Jacobian needs), equal to the two above.
struct ForceStiffness {
  double force_N = 0.0, stiffness_N_per_m = 0.0;
};
ForceStiffness sneddon_force_stiffness(double depth_m, double Estar_Pa, double radius_m);

/// The polynomial factor (>= 1) and its derivative with respect to depth.
double thickness_factor(double depth_m, double radius_m, const Thickness& t);
double thickness_factor_derivative_per_m(double depth_m, double radius_m, const Thickness& t);

/// Effective modulus from Young's modulus and back (rigid tip): E* = E / (1 - nu^2).
double effective_modulus_Pa(double E_Pa, double poisson);
double youngs_modulus_Pa(double Estar_Pa, double poisson);

}  // namespace palp::analysis
