// SPDX-License-Identifier: Apache-2.0
// MapAligner: the start of map_plan's touch at each point, along the work object's z or along
// the surface normal (a trace's, or a local trace's of four touches around the point).
#include "map_align.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace palp::detail {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kMaxTiltLimitRad = 80.0 / kDegPerRad;
constexpr double kMaxLocalOffsetM = 20e-3;
// a trace of the same plan touched along the work object's z at the plan's (x, y): its apexes
// lie there to the robot's position resolution; its work object is the rig's to file rounding
constexpr double kSamePointM = 0.1e-3;
constexpr double kSameOriginM = 0.01e-3;
constexpr double kSameAngleRad = 0.01 / kDegPerRad;

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char s[160];
  std::snprintf(s, sizeof s, f, a, b, c, d);
  return s;
}

std::string at(int row, int column) {
  return "point (row " + std::to_string(row) + ", column " + std::to_string(column) + ")";
}

double tilt_of(const double n[3]) { return std::acos(std::clamp(n[2], -1.0, 1.0)); }

/// The angle (rad) between two orientations.
double angle_between(const Pose& a, const Pose& b) {
  const proto::rb::Rotation r = proto::rb::transpose(transform_of(a).r) * transform_of(b).r;
  return std::acos(std::clamp((r.m[0][0] + r.m[1][1] + r.m[2][2] - 1.0) / 2.0, -1.0, 1.0));
}

void check_trace(const TracedSurface& t, const Rig& rig, const Plan& plan, double max_tilt) {
  const std::string what = "the alignment's trace";
  if (t.rows != plan.grid.rows || t.columns != plan.grid.columns)
    throw ConfigError(what + " is a " + std::to_string(t.rows) + " x " + std::to_string(t.columns) +
                      " grid, the plan " + std::to_string(plan.grid.rows) + " x " +
                      std::to_string(plan.grid.columns) + ": trace the plan to map");
  if (!t.complete || !t.normals_from_grid)
    throw ConfigError(
        what + " has no normals from a whole grid (" +
        (t.complete ? std::string("a point without contact") : "stopped: " + t.stopped_because) +
        "): finish or repeat the trace");
  const Pose& w = rig.work_object->pose;
  const double moved =
      std::hypot(t.work_object.x_m - w.x_m, t.work_object.y_m - w.y_m, t.work_object.z_m - w.z_m);
  const double turned = angle_between(t.work_object, w);
  if (moved > kSameOriginM || turned > kSameAngleRad)
    throw ConfigError(what + " was made in another pose of the work object (" +
                      fmt("%.3f mm, %.3f deg", moved * 1e3, turned * kDegPerRad) +
                      " from the rig's): trace it again after the touch-off");
  for (const TracePoint& p : t.points) {
    const double x = plan.x_m(p.column - 1), y = plan.y_m(p.row - 1);
    if (std::hypot(p.apex_x_m - x, p.apex_y_m - y) > kSamePointM)
      throw ConfigError(what + "'s " + at(p.row, p.column) + " was touched at " +
                        fmt("(%.3f, %.3f) mm, the plan's is at (%.3f, %.3f) mm", p.apex_x_m * 1e3,
                            p.apex_y_m * 1e3, x * 1e3, y * 1e3) +
                        ": a trace of another plan");
    if (tilt_of(p.normal) > max_tilt)
      throw ConfigError(what + "'s " + at(p.row, p.column) + ": the normal is tilted " +
                        fmt("%.1f deg, more than the maximum tilt %.1f deg",
                            tilt_of(p.normal) * kDegPerRad, max_tilt * kDegPerRad));
  }
}

}  // namespace

IndentationSettings with_current_offset(IndentationSettings s, double offset_A) {
  if (offset_A == 0.0) return s;
  s.start_A += offset_A;
  s.stop_A += offset_A;
  s.analysis.contact_current_A += offset_A;
  s.analysis.bias_current_A += offset_A;
  return s;
}

IdentificationSettings with_current_offset(IdentificationSettings s, double offset_A) {
  s.bias_A += offset_A;
  s.contact_current_A += offset_A;
  return s;
}

void MapAligner::check() const {
  const MapOptions& o = o_;
  if (o.align_trace && !o.align_to_normal)
    throw ConfigError("map options: a trace to align with, but align_to_normal is off");
  if (!(o.max_tilt_rad > 0 && o.max_tilt_rad <= kMaxTiltLimitRad))
    throw ConfigError("map options: max_tilt_rad is " + fmt("%g deg", o.max_tilt_rad * kDegPerRad) +
                      ", not in (0, 80] deg");
  if (!(o.local_trace_offset_m > 0 && o.local_trace_offset_m <= kMaxLocalOffsetM))
    throw ConfigError("map options: local_trace_offset_m is " +
                      fmt("%g mm", o.local_trace_offset_m * 1e3) + ", not in (0, 20] mm");
  if (o.align_trace) check_trace(*o.align_trace, rig_, plan_, o.max_tilt_rad);
}

MapAim MapAligner::aim(int row, int column, double clearance) {
  const double x = plan_.x_m(column - 1), y = plan_.y_m(row - 1);
  MapAim a;
  if (!o_.align_to_normal) {
    a.start = toucher_.tcp_at(x, y, -clearance);
    return a;
  }
  std::optional<Plane> plane;
  if (o_.align_trace) {
    const TracePoint& p =
        o_.align_trace
            ->points[static_cast<std::size_t>((row - 1) * plan_.grid.columns + column - 1)];
    plane = Plane{{p.x_m, p.y_m, p.z_m}, {p.normal[0], p.normal[1], p.normal[2]}};
    a.aligned_by = "trace";
  } else {
    plane = local_plane(x, y, clearance, a.reason);
    a.aligned_by = "local trace";
    if (!plane) {
      a.ok = false;
      return a;
    }
  }
  const double* n = plane->normal;
  a.tilt_rad = tilt_of(n);
  a.tool_axis.assign(n, n + 3);
  if (a.tilt_rad > o_.max_tilt_rad) {
    toucher_.release_coil();  // as after a touch without contact: the next point floats it again
    a.ok = false;
    a.reason =
        "the local normal is tilted " + fmt("%.1f deg, more than the maximum tilt %.1f deg",
                                            a.tilt_rad * kDegPerRad, o_.max_tilt_rad * kDegPerRad);
    return a;
  }
  // where the tangent plane meets the plan's (x, y): the touch lands there along the normal
  const double* c = plane->point;
  const double q[3] = {x, y, c[2] - (n[0] * (x - c[0]) + n[1] * (y - c[1])) / n[2]};
  a.start = toucher_.tcp_along(q, n, clearance);
  return a;
}

std::optional<MapAligner::Plane> MapAligner::local_plane(double x, double y, double clearance,
                                                         std::string& why) {
  TracedSurface s;
  s.rows = s.columns = 2;
  s.work_object = rig_.work_object->pose;
  s.tip_radius_m = rig_.tip_radius_m;
  s.contact_E_star_Pa = plan_.contact_E_star_Pa;
  const double d = o_.local_trace_offset_m;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      const double xt = x + (c == 0 ? -d : d), yt = y + (r == 0 ? -d : d);
      Touch t =
          toucher_.touch(toucher_.tcp_at(xt, yt, -clearance),
                         rig_.safe_height_m + rig_.max_approach_m, plan_.approach_speed_m_per_s);
      toucher_.rise_to(clearance);
      if (!t.ok) {
        why =
            "the local trace's touch at " + fmt("(%.3f, %.3f) mm: ", xt * 1e3, yt * 1e3) + t.reason;
        return std::nullopt;
      }
      t.at_rest.row = r + 1;
      t.at_rest.column = c + 1;
      t.at_rest.ok = true;
      s.points.push_back(t.at_rest);
    }
  s.resume_index = s.points.size();
  s.complete = true;
  finish_surface(s);
  // the tangent plane: through the mean of the four contact points, the mean of their normals
  Plane p{{0, 0, 0}, {0, 0, 0}};
  for (const TracePoint& q : s.points) {
    const double pt[3] = {q.x_m, q.y_m, q.z_m};
    for (int i = 0; i < 3; ++i) p.point[i] += pt[i] / 4, p.normal[i] += q.normal[i];
  }
  const double len = std::hypot(p.normal[0], p.normal[1], p.normal[2]);
  for (double& v : p.normal) v /= len;
  return p;
}

}  // namespace palp::detail
