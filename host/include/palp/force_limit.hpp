// SPDX-License-Identifier: Apache-2.0
// Ramps that stop at an object force (issue 24, docs/depth-sensitivity.md): the staircase's top
// current for a wanted object force F, and whether the coil may carry it.
//
//   palp::CoilLimits lim = palp::CoilLimits::of(probe.params());
//   palp::check_max_force(settings, 7.0, lim);                    // ConfigError naming the numbers
//   palp::IndentationSettings s = palp::settings_for_max_force(settings, 7.0, expected_depth_m);
//
// The firmware has no force stop: its ramp (RampProgram) steps the current and turns round only
// at its displacement limit. So the host chooses the top current from the paper's force model
// with the analysis' constants (IndentationParams):
//
//   F_o = K_f (i - I_c) - k_v delta   =>   i_top = I_c + (F + k_v delta_F) / K_f
//
// where delta_F, the depth at which the specimen carries F, is not known before the ramp: the
// caller gives an expected depth (a map takes the depth its previous point reached at the top,
// 0 for its first point: F_o then stops k_v delta short of F, 0.13 N at the pad's 3 mm, never
// above it). The step is shrunk (never grown) so that the staircase's top level is i_top exactly.
//
// The limits checked, for the worst depth the ramp can reach (its displacement limit, which
// must be set: it is the travel stop that bounds delta_F):
//   - the current clamp (the device's current_clamp_A): the firmware would clip the top;
//   - the firmware's I2t model (firmware/core/README.md: dE/dt = i^2 - I_cont^2 - E / tau,
//     E >= 0, trip at E_lim): the ramp's repetitions, repeated back to back with settle_s at
//     the start current between them (a map's points; the map's own pauses at 0 A only cool
//     further), must keep E below the model's warning level, 80 % of E_lim.
#pragma once

#include "palp/indent.hpp"
#include "palp/probe.hpp"

namespace palp {

/// The coil's limits as the firmware enforces them (protocol catalogue's Params).
struct CoilLimits {
  double current_clamp_A = 3.2;   ///< the commanded current never exceeds this
  double i2t_continuous_A = 2.0;  ///< the I2t model's continuous rating
  double i2t_limit_A2s = 60;      ///< its trip level above the continuous rating
  double i2t_tau_s = 120;         ///< its cooling time constant
  static CoilLimits of(const Params& p);
};

/// The share of the trip level above which the firmware warns (i2t_warning) and a force-limited
/// ramp is refused.
inline constexpr double kI2tWarningFraction = 0.8;

/// i_top = I_c + (F + k_v depth) / K_f, with the analysis' constants.
double top_current_for_force_A(const analysis::IndentationParams& a, double force_N,
                               double depth_m);

/// Peak of the firmware's I2t model, A^2 s, over the settings' ramp (all repetitions) repeated
/// back to back with settle_s at start_A between, from a cold coil to its periodic state.
double ramp_i2t_peak_A2s(const IndentationSettings& s, const CoilLimits& lim);

/// Throws ConfigError, naming the numbers, when max_force_N is not a positive finite force, the
/// settings have no displacement limit, or the top current for max_force_N at the displacement
/// limit's depth exceeds the clamp or heats the I2t model beyond its warning level.
void check_max_force(const IndentationSettings& s, double max_force_N, const CoilLimits& lim);

/// s with its top at object force max_force_N for a specimen expected to carry it at
/// expected_depth_m (clamped to 0 .. the displacement limit): stop_A = top_current_for_force_A,
/// step_A shrunk so that the top is a level of the staircase.
IndentationSettings settings_for_max_force(IndentationSettings s, double max_force_N,
                                           double expected_depth_m);

/// Where a run's first repetition peaked: its top commanded level's mean object force and depth
/// below the floating position (run.float_z_m), F_o as above with the run's analysis constants.
struct RampTop {
  double force_N = 0;
  double depth_m = 0;
};
/// Absent when the run recorded no loading sample.
std::optional<RampTop> ramp_top_of(const IndentationRun& run);

}  // namespace palp
