// SPDX-License-Identifier: Apache-2.0
// Force-constant calibration in free air (issue 7): the coil is held at static currents along
// its stroke (a slow staircase, both ways) and each settled level gives a balance
//
//   K_f(s) i = k_v (s - s_rest) + c          (gravity and preload in the constant)
//
// with s the stroke position (from the stroke origin) and k_v the spring's known stiffness.
// K_f(s) is piecewise linear over nodes s_0 < ... < s_n (constant beyond), so the balance is
// linear in the node values and one constant: a least-squares fit of the absolute balance, not
// of k_v ds/di (a sloped K_f biases that one). SI units.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "palp/protocol/messages.hpp"
#include "palp/recording_types.hpp"

namespace palp::analysis {

/// One settled level: mean stroke position and mean measured current over the level's settled
/// part, with their standard deviations and sample count.
struct KfStaticPoint {
  double stroke_m = 0, i_A = 0;
  double stroke_sd_m = 0, i_sd_A = 0;
  std::size_t samples = 0;
};

/// Cuts a staircase recording into its levels with the ramp's exact schedule (program start
/// found from the commanded current's first step) and averages the last `settled_fraction` of
/// each level. stroke = z - stroke_origin_z. ConfigError for a recording that does not cover
/// the ramp or a level with fewer than 3 samples.
std::vector<KfStaticPoint> kf_static_points(const Recording& rec, const proto::LoadRamp& ramp,
                                            std::uint32_t control_rate_Hz,
                                            double stroke_origin_z_m,
                                            double settled_fraction = 0.5);

struct KfCalibration {
  std::vector<double> node_stroke_m;   ///< increasing
  std::vector<double> kf_N_per_A;      ///< at each node
  std::vector<double> kf_se_N_per_A;
  double c_N = 0, c_se_N = 0;
  double k_v_N_per_m = 0;
  double residual_rms_N = 0;           ///< of the balance
  std::size_t points = 0;
  /// Set when c, and with it K_f, is poorly determined (see KfAnchor): one sentence with the
  /// numbers and what to do. Empty otherwise.
  std::string warning;
};

/// Evenly spaced nodes over the points' stroke range, at most max_nodes (the calibration block
/// holds 16) and at least two points between neighbours; at most points - 3 nodes (what
/// fit_kf_table needs). ConfigError for fewer than 4 points or points at one stroke.
std::vector<double> kf_nodes_for(std::span<const KfStaticPoint> points, std::size_t max_nodes = 16);

/// The least-squares fit. ConfigError for k_v <= 0, nodes not increasing, fewer points than
/// unknowns + 2, a node with no point within its neighbours' span (unidentifiable).
KfCalibration fit_kf_table(std::span<const KfStaticPoint> points, double k_v_N_per_m,
                           std::span<const double> node_stroke_m);

/// A known K_f at one stroke position (e.g. the paper's 2.918 N/A at 24 mm of travel). Free-air
/// static points fix K_f(s) only up to K_f(s) + dc / i(s): they lie on one curve i(s), and every
/// constant c has its exact K_f = (k_v s + c) / i. A fit with few nodes is held by their
/// piecewise-linear shape; with many (kf_nodes_for's 16) it is nearly singular, c and K_f wander
/// with the noise, and KfCalibration::warning says so. The anchor fixes K_f there, and so c.
struct KfAnchor {
  double stroke_m = 0;
  double kf_N_per_A = 0;
};

/// The fit with K_f(anchor.stroke_m) = anchor.kf_N_per_A (a constraint). ConfigError as above,
/// and for an anchor that is not finite or K_f <= 0.
KfCalibration fit_kf_table(std::span<const KfStaticPoint> points, double k_v_N_per_m,
                           std::span<const double> node_stroke_m, const KfAnchor& anchor);

}  // namespace palp::analysis
