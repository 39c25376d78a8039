// SPDX-License-Identifier: Apache-2.0
// palp::Pose: a tool-centre-point pose as a KUKA controller gives it, in SI: x, y, z in the
// robot's base frame (m), then A, B, C, the ZYX Euler angles in rad (A about z, B about the new y,
// C about the newest x). Its own header so the analysis (surface.hpp) uses poses without the
// robot client's headers.
#pragma once

namespace palp {

/// A TCP pose: position in m, KUKA ZYX Euler angles in rad.
struct Pose {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double a_rad = 0.0, b_rad = 0.0, c_rad = 0.0;
};

}  // namespace palp
