// SPDX-License-Identifier: Apache-2.0
// The guarded-approach touch shared by trace_surface and touch_off (trace.hpp has the sequence).
#pragma once

#include <array>
#include <functional>
#include <optional>

#include "palp/analysis/surface.hpp"
#include "palp/protocol/robot_bridge/pose.hpp"
#include "palp/trace.hpp"

namespace palp::detail {

proto::rb::Transform transform_of(const Pose& p);
Pose pose_of(const proto::rb::Transform& t);
/// A measured point as the surface analysis takes it (base frame; the tool's z is the axis).
analysis::ApproachAtRest approach_at_rest(const TracePoint& measured);

/// KUKA A, B, C (rad; in the returned Pose, position zero) of the tool orientation whose z axis
/// is `axis` (unit, base frame) with A kept at a_rad, so the tool does not spin about the base's
/// z: R = Rz(A) Ry(B) Rx(C) has z column Rz(A) (sin B cos C, -sin C, cos B cos C), which gives
/// sin C and B up to the sign of cos C; of the two solutions the one nearer (b_near, c_near).
/// ConfigError when that axis leaves B undefined (cos C = 0: the axis horizontal across Rz(A) x).
Pose orientation_along(const double axis[3], double a_rad, double b_near_rad, double c_near_rad);

/// The probe's whole stroke: the tip never reaches further ahead of the TCP.
inline constexpr double kFullStrokeM = 34e-3;

class Toucher {
 public:
  struct Cancelled {};

  Toucher(Probe& probe, Robot& robot, const Rig& rig, std::function<bool()> cancelled);

  /// Tool, contact-output line, and a floating coil (once).
  void prepare();
  /// From `start` (base frame; the arm goes there first at the travel speed) approach along the
  /// tool's z: a fast search, back off, settle, the slow approach; the arm then rests in contact.
  /// travel_m: the search's maximum travel from start.
  Touch touch(const Pose& start, double travel_m,
              std::optional<double> approach_speed_m_per_s = std::nullopt);
  /// The floating coil's stroke position (m) measured by prepare(): where the tip is ahead of
  /// the TCP (the tip apex at stroke origin) while no contact pushes it; measured again by a
  /// touch whose start turns the tool (the coil's weight along its axis changes with the tilt).
  double floating_stroke_m() const { return floating_stroke_m_; }
  /// Moves along the tool's -z by `distance` at the travel speed.
  void back_off(double distance_m);
  /// Stop the arm, zero the coil current, each on its own (one failing must not skip the other).
  void make_safe();
  /// Zeroes the coil current (the watch's hold current stays on between touches).
  void release_coil();
  void check_cancelled() const;

  /// Waits this much device time (virtual time in palp-sim).
  void wait_device(double dt_s);

  // --- in a work object (trace, map) ---------------------------------------------------------
  void set_work_object(const Pose& work_object);
  /// The TCP over work-object point (x, y, z) with the tool's z along the work object's z.
  Pose tcp_at(double x, double y, double z) const;
  /// The TCP `distance_m` back from work-object point `point_m` along `normal` (unit, work-object
  /// frame, into the specimen), the tool's z along that normal and the work object's A kept
  /// (orientation_along): the start of an approach normal to the surface (map --align normal).
  Pose tcp_along(const double point_m[3], const double normal[3], double distance_m) const;
  /// Turns the tool to the work object's orientation where it is (before a tilted map's first
  /// prepare(): the upright floating position is the reference of compensate_tilt).
  void turn_upright();
  /// A turned tool's coil carries another part of its weight along the axis, so at the same
  /// current it floats elsewhere (3.4 mm back at 25 degrees in palp-sim) and works at another
  /// stroke position, where K_f(s) differs. With this on, a touch whose start turns the tool
  /// floats the coil again with the current that puts it where it floats upright (tool along the
  /// work object's z, measured by the first prepare() so): current_offset_A() more, from the
  /// floating positions, k_v (s_upright - s) / K_f. Off by default (trace, touch-off).
  void compensate_tilt(bool on) { compensate_tilt_ = on; }
  /// What the tilt compensation adds to the watch current now (A); the ramp adds it too.
  double current_offset_A() const { return offset_A_; }
  /// Straight up along the work object's -z until the TCP is `clearance` above its z = 0,
  /// keeping the tool's orientation (a tilted tool rises tilted).
  void rise_to(double clearance_m);
  /// make_safe(), then up until the tip is clear of the safe height even at full stroke.
  void make_safe_and_raise();

 private:
  struct Approach;
  /// Arms the watch and approaches until the watch fires, the robot's input stops the arm, or
  /// travel_m; an approach the input stopped although the watch saw no contact (the robot still
  /// saw the previous contact's line) is started again.
  Approach approach(double speed, double travel_m);
  bool stopped_by_the_input(const MotionResult& m) const;
  void arm();
  double stroke_now_m();

  Probe& probe_;
  Robot& robot_;
  const Rig& rig_;
  std::function<bool()> cancelled_;
  bool floating_ = false;
  double floating_stroke_m_ = 0.0;
  std::array<double, 3> floating_axis_{0, 0, 1};  // the tool's z (base) where it was measured
  bool compensate_tilt_ = false;
  double offset_A_ = 0.0;                         // added to the watch current (the tilt's)
  std::optional<double> upright_stroke_m_;        // floating with the work object's z, no offset
  proto::rb::Transform wo_, wo_inv_;  // the work object (identity until set)
};

}  // namespace palp::detail
