// The guarded-approach touch shared by trace_surface and touch_off (trace.hpp has the sequence).
#pragma once

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
  /// the TCP (the tip apex at stroke origin) while no contact pushes it.
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

 private:
  struct Approach;
  Approach approach(double speed, double travel_m);
  void arm();
  double stroke_now_m();

  Probe& probe_;
  Robot& robot_;
  const Rig& rig_;
  std::function<bool()> cancelled_;
  bool floating_ = false;
  double floating_stroke_m_ = 0.0;
};

}  // namespace palp::detail
