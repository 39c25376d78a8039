// SPDX-License-Identifier: Apache-2.0
// RobotArm: the KUKA iiwa as the robot-bridge emulator needs it, in virtual time, no I/O.
//
// What is modelled (and what is not):
//   - The flange pose in the robot's base frame and the active tool (the TCP frame on the
//     flange): tcp = flange * tool. Poses use robot_bridge/pose.hpp (KUKA ZYX, m and rad).
//   - Linear Cartesian motion of the TCP with a trapezoidal speed profile: from rest, at
//     `accel` up to the commanded speed, cruise, and at `accel` down to rest at the target
//     (a triangle when the move is too short to reach the speed). The orientation is
//     interpolated with the position along the same profile (the rotation from start to
//     target about its fixed axis, by the fraction of the path done). The path length is
//     max(translation, rotation angle x kRotationLengthM), so a pure re-orientation also
//     takes time.
//   - PTP (joint-interpolated) motion is modelled as a linear move (no joint model): the same
//     path, at ptp_speed_m_per_s x permille / 1000.
//   - A stop brakes on the path: the arm keeps its profile for `stop_latency_s`, then
//     decelerates at `brake_decel` to rest (never past the target). Braking distance from a
//     speed v: v * latency + v^2 / (2 * brake_decel).
//   - The workspace: the TCP position of a target within `workspace_radius_m` of the base
//     origin and at z >= 0. A target outside is unreachable (the move is refused). Only the
//     target is checked: the sphere-and-half-space is convex, so a straight path between two
//     points inside stays inside; the start pose itself may lie outside (a move back in works).
//   - No joints (the bridge reports zeros), no dynamics beyond the profile, no collisions.
#pragma once

#include "palp/protocol/robot_bridge/pose.hpp"

namespace palp::plant {

using Transform = proto::rb::Transform;

struct RobotArmConfig {
  double accel_m_per_s2 = 0.5;          ///< path acceleration and deceleration of a move
  double brake_decel_m_per_s2 = 2.0;    ///< deceleration of a stop
  double stop_latency_s = 0.004;        ///< from stop() to the start of braking
  double workspace_radius_m = 0.8;      ///< targets' TCP within this sphere around the base
  double ptp_speed_m_per_s = 1.0;       ///< a PTP move at 1000 permille
};

/// A pose from SI parts: position in m, KUKA A, B, C in rad.
Transform pose_from_xyzabc(double x_m, double y_m, double z_m, double a_rad, double b_rad,
                           double c_rad);

class RobotArm {
 public:
  /// Starts stationary at this flange pose with the flange as the TCP (tool 0). Throws
  /// std::invalid_argument when a config value is out of range.
  explicit RobotArm(const Transform& flange, RobotArmConfig config = {});

  /// Path length a rotation of one radian counts for.
  static constexpr double kRotationLengthM = 0.1;

  // --- poses ---------------------------------------------------------------------------
  const Transform& flange() const { return flange_; }
  const Transform& tool() const { return tool_; }
  /// The TCP in the base frame: flange * tool.
  Transform tcp() const;
  /// Makes `tool` (the TCP frame on the flange) the active tool. Refused (false) while moving.
  bool set_tool(const Transform& tool);
  /// Whether the flange pose that puts the TCP at tcp_target is inside the workspace.
  bool reachable(const Transform& tcp_target) const;

  // --- motion --------------------------------------------------------------------------
  /// Starts a linear move of the TCP to tcp_target at speed_m_per_s (> 0). Returns false and
  /// does nothing when the target is unreachable, the speed is not positive, or the arm moves.
  bool move_lin(const Transform& tcp_target, double speed_m_per_s);
  /// move_lin by an offset given in the current TCP frame (target = tcp * offset).
  bool move_lin_rel(const Transform& offset_in_tool, double speed_m_per_s);
  /// A PTP move, modelled as move_lin at ptp_speed x permille / 1000.
  bool move_ptp(const Transform& tcp_target, int speed_permille);
  /// Brakes on the path: the profile runs on for the stop latency, then the arm decelerates at
  /// brake_decel to rest. Does nothing when stationary or already stopping.
  void stop();
  /// Advances virtual time by dt_s >= 0.
  void step(double dt_s);

  bool moving() const { return moving_; }
  bool stopping() const { return stop_requested_; }
  /// True when the last move ended at its target (not cut short by a stop).
  bool reached_target() const { return reached_; }
  /// Path speed now, m/s.
  double speed_m_per_s() const { return v_; }
  /// Path length done by the current (or last) move, m.
  double travelled_m() const { return s_; }
  const RobotArmConfig& config() const { return config_; }

 private:
  void place(double s);
  double profile_s(double t) const;  // path position of the unbraked trapezoid at time t
  double profile_v(double t) const;

  RobotArmConfig config_;
  Transform flange_;
  Transform tool_;

  // the move in progress (flange poses: the tool cannot change while moving)
  bool moving_ = false;
  bool reached_ = true;
  Transform start_;
  double dp_[3] = {0, 0, 0};    // flange translation start -> target
  double axis_[3] = {0, 0, 1};  // rotation axis of start -> target, in the start frame
  double angle_ = 0.0;          // rad
  double length_ = 0.0;         // path length, m
  double vmax_ = 0.0, t_ = 0.0, t_acc_ = 0.0, t_total_ = 0.0;
  double s_ = 0.0, v_ = 0.0;
  // a stop
  bool stop_requested_ = false;
  double stop_at_t_ = 0.0;     // when braking starts (move time)
  double brake_s0_ = 0.0, brake_v0_ = 0.0;
  bool braking_ = false;
};

}  // namespace palp::plant
