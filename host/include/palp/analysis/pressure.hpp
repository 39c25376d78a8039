// SPDX-License-Identifier: Apache-2.0
// Pressure analysis (issue 6, paper §V-D): plain functions over Eigen data, no I/O, no device.
//
// SI everywhere (N, Pa, m, m^3); the CLI converts to lab units (mm^3). Pressures are gauge
// pressures (the rise above the channel's zeroed reading), as the device streams them.
//
//   Pressure against force, per channel, on the loading branch: p = slope F + intercept by least
//   squares (slope in Pa/N, R^2, standard errors). The paper regresses on the contact force; the
//   caller chooses the force (analyze_pressure uses the object force F_o = K_f (i - I_c) -
//   k_v (z - z_c) of the samples at i >= I_c).
//   Hysteresis of one load/unload cycle: both branches interpolated on a common force grid over
//   the force range they share; loop_area = integral of (p_unload - p_load) dF (Pa N, positive
//   when unloading lies above loading), ratio = loop_area / (force range x loading pressure
//   range) (0 = none), max_gap = the largest |p_unload - p_load| on the grid.
//   Boyle (isothermal: the ramps are slow against the channel's thermal time): P1 V1 = P2 V2 with
//   P1 the ambient pressure and P2 = P1 + dP, so dV = V1 (1 - P1 / P2). The adiabatic bound
//   (P V^gamma constant, gamma = 1.4 for air) is dV = V1 (1 - (P1 / P2)^(1 / gamma)); the
//   isothermal estimate overstates a fast step's dV by up to 40 % (analysis-notes.md).
//   The enclosed volume V1 is the channel's cylinder plus the tube's bore: the paper's
//   Ø5 mm x 90 mm (shallow) and x 100 mm (deep) channels with a 1/16 in x 50 cm tube give
//   2757 / 2953 mm^3, and its rises of 573 / 167 Pa give dV = 15.5 / 4.86 mm^3.
//   (The paper's "ideal" 35.57 mm^3 for 3 mm of probe travel turned wholly into channel collapse
//   is not reproduced here: the paper gives no formula for it; a paraboloid tip's displaced
//   volume pi R delta^2 / 2 is 35.34 mm^3 at 3 mm.)
//
// Errors: malformed input (sizes differ, NaN/inf, a non-positive geometry or pressure) throws
// palp::ConfigError naming the problem, except in analyze_pressure, where data it cannot use (a
// NaN pressure sample, no contact) throws palp::DataError; a value that cannot be computed from
// valid input is an absent Value with a reason, never NaN.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "palp/analysis/indentation.hpp"

namespace palp::analysis {

/// Least-squares line y = slope x + intercept.
struct LineFit {
  Value slope, intercept, slope_se, intercept_se, r2;  ///< absent with the reason when n < 3
                                                        ///< or x does not vary
  int n = 0;
};
/// Throws ConfigError when the sizes differ or a value is not finite.
LineFit fit_line(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

/// Hysteresis of one cycle (see the header comment); absent values when a branch has fewer than
/// 2 samples or the branches share no force range.
struct PressureHysteresis {
  Value loop_area_Pa_N, ratio, max_gap_Pa;
};
PressureHysteresis pressure_hysteresis(const Eigen::VectorXd& load_force_N,
                                       const Eigen::VectorXd& load_p_Pa,
                                       const Eigen::VectorXd& unload_force_N,
                                       const Eigen::VectorXd& unload_p_Pa, int grid_points = 200);

/// One channel's pressure against force (loading branches pooled over repetitions).
struct ChannelPressure {
  int channel = 0;           ///< 1..6 as on the pad
  LineFit fit;               ///< p (Pa) against F (N): slope in Pa/N
  Value rise_Pa;             ///< mean over repetitions of p at the peak force minus p at the
                             ///< first contact sample (what Boyle's law takes as dP)
  Value rise_sd_Pa;          ///< its s.d. over repetitions (absent below 2)
  std::vector<PressureHysteresis> hysteresis;  ///< one per repetition
  Value hysteresis_ratio_mean;                 ///< mean ratio over repetitions with one
};
struct PressureResult {
  std::vector<ChannelPressure> channels;
  double contact_z_m = 0.0;  ///< the depth origin of F_o
  int n_loading = 0;         ///< loading samples at i >= I_c used for the fits
};
/// p_Pa: one column per channel (n x channels, channel k + 1 in column k), the same samples as
/// the curve. Throws ConfigError when the sizes differ or the contact point is not finite,
/// DataError on a NaN sample or when no loading sample reaches I_c.
PressureResult analyze_pressure(const Curve& c, const Eigen::MatrixXd& p_Pa,
                                const IndentationParams& p, double contact_z_m);

/// A channel and the tube to its transducer (cylinders).
struct ChannelGeometry {
  double channel_diameter_m = 5e-3;
  double channel_length_m = 90e-3;
  double tube_bore_m = 1.5875e-3;  ///< 1/16 in
  double tube_length_m = 0.5;
};
/// V1 = pi/4 (d_c^2 L_c + d_t^2 L_t). Throws ConfigError for a non-positive or non-finite size
/// (a tube length of 0 is allowed: no tube).
double enclosed_volume_m3(const ChannelGeometry& g);

inline constexpr double kAmbientPressurePa = 101325.0;
inline constexpr double kAirHeatCapacityRatio = 1.4;

struct BoyleResult {
  double V1_m3 = 0, P1_Pa = 0, P2_Pa = 0;
  double dV_isothermal_m3 = 0;  ///< V1 (1 - P1/P2), positive for a compression
  double dV_adiabatic_m3 = 0;   ///< V1 (1 - (P1/P2)^(1/gamma))
};
/// Throws ConfigError for V1 <= 0, P1 <= 0, P1 + dP <= 0, gamma <= 1 or a non-finite input.
BoyleResult boyle_volume_change(double V1_m3, double pressure_change_Pa,
                                double ambient_Pa = kAmbientPressurePa,
                                double gamma = kAirHeatCapacityRatio);

}  // namespace palp::analysis
