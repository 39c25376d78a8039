// SPDX-License-Identifier: Apache-2.0
// trace_surface and touch_off: the guarded-approach sequence of trace.hpp over a grid.
#include "palp/trace.hpp"

#include <algorithm>
#include <cmath>

#include "palp/analysis/surface.hpp"
#include "toucher.hpp"

namespace palp {

namespace {

using detail::Toucher;

class Tracer {
 public:
  Tracer(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan, const TraceOptions& o)
      : rig_(rig), plan_(plan), o_(o), toucher_(probe, robot, rig, o.cancelled) {
    rig.validate();
    plan.validate();
    if (!rig.work_object)
      throw ConfigError("the rig has no registered work object: run `palpctl touch-off` first");
    if (!plan.work_object.empty() && plan.work_object != rig.work_object->name)
      throw ConfigError("the plan is in work object '" + plan.work_object + "' but the rig's is '" +
                        rig.work_object->name + "': touch off '" + plan.work_object + "' first");
    toucher_.set_work_object(rig.work_object->pose);
  }

  TracedSurface run() {
    TracedSurface s = o_.resume ? *o_.resume : TracedSurface{};
    const std::size_t total = static_cast<std::size_t>(plan_.grid.rows) * static_cast<std::size_t>(plan_.grid.columns);
    if (o_.resume && (s.rows != plan_.grid.rows || s.columns != plan_.grid.columns || s.points.size() > total ||
                      s.resume_index != s.points.size()))
      throw ConfigError("the trace to resume does not belong to this plan (" + std::to_string(s.rows) + " x " +
                        std::to_string(s.columns) + " grid, " + std::to_string(s.points.size()) +
                        " points kept; the plan is " + std::to_string(plan_.grid.rows) + " x " +
                        std::to_string(plan_.grid.columns) + ")");
    s.plan_name = plan_.name;
    s.rows = plan_.grid.rows;
    s.columns = plan_.grid.columns;
    s.work_object = rig_.work_object->pose;
    s.tip_radius_m = rig_.tip_radius_m;
    s.contact_E_star_Pa = plan_.contact_E_star_Pa;
    s.complete = false;
    s.stopped_because.clear();
    s.stopped_error = nullptr;
    try {
      toucher_.check_cancelled();
      toucher_.rise_to(rig_.safe_height_m + detail::kFullStrokeM);  // whatever the coil does, the tip is clear
      toucher_.prepare();
      for (std::size_t k = s.resume_index; k < total; ++k) {
        toucher_.check_cancelled();
        const int row = static_cast<int>(k) / s.columns + 1;
        const int column = static_cast<int>(k) % s.columns + 1;
        s.points.push_back(trace_point(row, column));
        s.resume_index = k + 1;
        toucher_.rise_to(tip_clearance());
        if (o_.progress) o_.progress(TraceProgress{s.resume_index, total, &s.points.back(), &s});
      }
      toucher_.release_coil();
      s.complete = true;
    } catch (const Toucher::Cancelled&) {
      s.stopped_because = "cancelled";
      toucher_.make_safe_and_raise();
    } catch (const std::exception& e) {
      s.stopped_because = e.what();
      s.stopped_error = std::current_exception();
      toucher_.make_safe_and_raise();
    }
    finish_surface(s);
    return s;
  }

 private:
  /// TCP height (work-object z, negative above) that puts the floating tip at the safe height.
  double tip_clearance() const { return rig_.safe_height_m + toucher_.floating_stroke_m(); }

  TracePoint trace_point(int row, int column) {
    const Pose start = toucher_.tcp_at(plan_.x_m(column - 1), plan_.y_m(row - 1), -tip_clearance());
    Touch t = toucher_.touch(start, rig_.safe_height_m + rig_.max_approach_m, plan_.approach_speed_m_per_s);
    TracePoint pt = t.at_rest;
    pt.row = row;
    pt.column = column;
    pt.ok = t.ok;
    pt.reason = t.reason;
    return pt;
  }

  const Rig& rig_;
  const Plan& plan_;
  const TraceOptions& o_;
  Toucher toucher_;
};

}  // namespace

TracedSurface trace_surface(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan,
                            const TraceOptions& options) {
  return Tracer(probe, robot, rig, plan, options).run();
}

Pose touch_off(Probe& probe, Robot& robot, const Rig& rig, const Pose (&start)[3],
               std::optional<double> contact_E_star_Pa, std::function<bool()> cancelled) {
  rig.validate();
  Toucher toucher(probe, robot, rig, std::move(cancelled));
  analysis::Vec3 apex[3];
  analysis::Vec3 axis = analysis::Vec3::UnitZ();
  try {
    for (int k = 0; k < 3; ++k) {
      const Touch t = toucher.touch(start[k], rig.max_approach_m);
      if (!t.ok) throw ConfigError("touch-off point " + std::to_string(k + 1) + ": " + t.reason);
      // the apex at zero force (the normal is unknown yet: the approach axis)
      const analysis::ApproachAtRest a = detail::approach_at_rest(t.at_rest);
      analysis::IndentationSource src;
      src.e_star_Pa = contact_E_star_Pa;
      src.contact_stiffness_N_per_m = t.at_rest.contact_stiffness_N_per_m;
      apex[k] = analysis::contact_point(a, src, rig.tip_radius_m, a.approach_dir).apex_zero_force_m;
      axis = a.approach_dir;
      toucher.back_off(rig.safe_height_m);
    }
    toucher.release_coil();
  } catch (const Toucher::Cancelled&) {
    toucher.make_safe();
    throw Error("touch-off cancelled; the arm is stopped and the coil current is zero");
  } catch (...) {
    toucher.make_safe();
    throw;
  }
  // the three apexes are the three contact points shifted by the same R (axis - n) (n: the
  // plane's normal into the specimen), so their plane is parallel to the surface: the frame's
  // orientation is right, and its origin moves back by that shift onto the surface
  Pose frame = analysis::register_work_object(apex[0], apex[1], apex[2], axis);
  const analysis::Vec3 n = analysis::frame_z_axis(frame);
  const analysis::Vec3 shift = rig.tip_radius_m * (axis - n);
  frame.x_m -= shift.x();
  frame.y_m -= shift.y();
  frame.z_m -= shift.z();
  return frame;
}

}  // namespace palp
