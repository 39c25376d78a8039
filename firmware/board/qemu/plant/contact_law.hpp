// SPDX-License-Identifier: Apache-2.0
// The scene's contact law in single precision: the exact Sneddon sphere (tip radius R = 2.5 mm)
// on solid_1d's bonded 15 mm layer at position 3 (Dimitriadis bottom effect), Kelvin-Voigt
// viscosity and a participating mass: hil/plant README.md "Equations" (Contact) with the numbers
// of hil/plant/phantoms/solid_1d.phantom. No series spring: solid_1d's structural compliance is
// 0 at every position.
//
// The Sneddon sphere, delta = a atanh(a/R), F = E* R^2 [(1 + u^2) atanh(u) - u] with u = a/R,
// dF/d(delta) = 2 E* a, comes from a table of its two smooth factors g(d) = u / sqrt(d) and
// h(d) = S / d^1.5 (d = delta/R, S = F / (E* R^2)), computed in double at compile time from the
// exact law and stored as float: 4-point Lagrange cubics in 256 cells over d in [0, 4]
// (10 mm; the front stop ends the stroke at 9 mm of depth in this scene).
#pragma once

namespace palp::qemu {

/// The law's numbers (hil/plant/phantoms/solid_1d.phantom, position 3; the tip: PlantConfig).
struct ContactConstants {
  static constexpr float kTipRadius_m = 2.5e-3f;          // paper §II-A: PLA hemisphere
  static constexpr float kEStar_Pa = 125764.0f;           // solid_1d e_star_Pa (tuned, hil README)
  static constexpr float kLayerThickness_m = 0.015f;      // solid_1d layer_thickness_m, pos. 3
  static constexpr float kRetardationTime_s = 2.124e-3f;  // solid_1d retardation_time_s, pos. 3
  static constexpr float kParticipatingMass_kg = 0.01416f;  // solid_1d participating_mass_kg
  static constexpr float kMassEngageDepth_m = 1.0e-3f;      // solid_1d mass_engage_depth_m
  static constexpr int kTableCells = 256;                   // cells over d in [0, kTableMaxDepth]
  static constexpr float kTableMaxDepth = 4.0f;             // d = delta / R (hil: same span)
};

/// Relaxed elastic force and its tangent at one depth.
struct ContactPoint {
  float force_N = 0.0f;
  float stiffness_N_per_m = 0.0f;
};

/// The elastic law at indentation depth_m: zero for depth <= 0; beyond the table (deeper than
/// 10 mm, out of the stroke) the table's last value.
ContactPoint contact_elastic(float depth_m);

}  // namespace palp::qemu
