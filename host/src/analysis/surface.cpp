// SPDX-License-Identifier: Apache-2.0
// Surface analysis: touch-off registration, zero-force contact points, grid normals and tilts.
#include "palp/analysis/surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "palp/error.hpp"
#include "palp/protocol/robot_bridge/pose.hpp"

namespace palp::analysis {
namespace {

[[noreturn]] void fail(const char* fn, const std::string& problem) {
  throw ConfigError(std::string(fn) + ": " + problem);
}

void require_finite(const char* fn, const char* what, const Vec3& v) {
  if (!v.allFinite()) fail(fn, std::string(what) + " is not finite");
}

Vec3 unit_direction(const char* fn, const char* what, const Vec3& v) {
  require_finite(fn, what, v);
  const double n = v.norm();
  if (!(n > 0.0)) fail(fn, std::string(what) + " is zero");
  return v / n;
}

Eigen::Matrix3d rotation_of(const Pose& f) {
  const proto::rb::Rotation r = proto::rb::rotation_from_abc(f.a_rad, f.b_rad, f.c_rad);
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = r.m[i][j];
  return m;
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

Pose register_work_object(const Vec3& p_origin, const Vec3& p_on_x_axis, const Vec3& p_in_plane,
                          const Vec3& approach_dir) {
  constexpr const char* fn = "register_work_object";
  require_finite(fn, "the origin", p_origin);
  require_finite(fn, "the point on the x axis", p_on_x_axis);
  require_finite(fn, "the point in the plane", p_in_plane);
  const Vec3 dir = unit_direction(fn, "the approach direction", approach_dir);
  const Vec3 ex = p_on_x_axis - p_origin, e3 = p_in_plane - p_origin;
  if (!(ex.norm() > 0.0)) fail(fn, "the origin and the point on the x axis coincide");
  if (!(e3.norm() > 0.0)) fail(fn, "the origin and the point in the plane coincide");
  const Vec3 normal = ex.cross(e3);
  if (!(normal.norm() > 1e-6 * ex.norm() * e3.norm())) {
    fail(fn, "the three points are collinear: they do not define a plane");
  }
  const Vec3 x = ex.normalized();
  Vec3 z = normal.normalized();
  const double along = z.dot(dir);
  if (std::abs(along) < 1e-6) fail(fn, "the approach direction lies in the plane of the points");
  if (along < 0.0) z = -z;
  const Vec3 y = z.cross(x);
  proto::rb::Rotation r;
  for (int i = 0; i < 3; ++i) {
    r.m[i][0] = x[i];
    r.m[i][1] = y[i];
    r.m[i][2] = z[i];
  }
  Pose pose;
  pose.x_m = p_origin.x();
  pose.y_m = p_origin.y();
  pose.z_m = p_origin.z();
  proto::rb::abc_from_rotation(r, pose.a_rad, pose.b_rad, pose.c_rad);
  return pose;
}

Vec3 frame_to_base(const Pose& frame, const Vec3& p_frame) {
  return rotation_of(frame) * p_frame + Vec3(frame.x_m, frame.y_m, frame.z_m);
}

Vec3 base_to_frame(const Pose& frame, const Vec3& p_base) {
  return rotation_of(frame).transpose() * (p_base - Vec3(frame.x_m, frame.y_m, frame.z_m));
}

Vec3 frame_z_axis(const Pose& frame) { return rotation_of(frame).col(2); }

double hertz_indentation_m(double force_N, const IndentationSource& source, double tip_radius_m) {
  constexpr const char* fn = "hertz_indentation_m";
  if (!std::isfinite(force_N) || force_N < 0.0) fail(fn, "the force must be finite and >= 0 N");
  if (!std::isfinite(tip_radius_m) || !(tip_radius_m > 0.0)) {
    fail(fn, "the tip radius must be positive");
  }
  if (source.e_star_Pa) {
    const double e = *source.e_star_Pa;
    if (!std::isfinite(e) || !(e > 0.0)) fail(fn, "E* must be positive");
    return std::cbrt(std::pow(3.0 * force_N / (4.0 * e * std::sqrt(tip_radius_m)), 2.0));
  }
  if (source.contact_stiffness_N_per_m) {
    const double k = *source.contact_stiffness_N_per_m;
    if (!std::isfinite(k) || !(k > 0.0)) fail(fn, "the contact stiffness must be positive");
    return 1.5 * force_N / k;
  }
  return 0.0;
}

ContactPoint contact_point(const ApproachAtRest& at_rest, const IndentationSource& source,
                           double tip_radius_m, const Vec3& normal_into_specimen) {
  constexpr const char* fn = "contact_point";
  require_finite(fn, "the TCP", at_rest.tcp_m);
  const Vec3 dir = unit_direction(fn, "the approach direction", at_rest.approach_dir);
  if (std::abs(at_rest.approach_dir.norm() - 1.0) > 1e-9) {
    fail(fn, "the approach direction must be a unit vector");
  }
  const Vec3 n = unit_direction(fn, "the normal", normal_into_specimen);
  if (!std::isfinite(at_rest.stroke_m)) fail(fn, "the stroke position is not finite");
  if (!(n.dot(dir) > 0.0)) fail(fn, "the normal must point into the specimen (n . dir > 0)");
  ContactPoint out;
  out.indentation_m = hertz_indentation_m(at_rest.detection_force_N, source, tip_radius_m);
  const Vec3 apex = at_rest.tcp_m + at_rest.stroke_m * dir;
  out.apex_zero_force_m = apex - out.indentation_m * dir;
  out.sphere_centre_m = out.apex_zero_force_m - tip_radius_m * dir;
  out.point_m = out.sphere_centre_m + tip_radius_m * n;
  return out;
}

GridNormals grid_normals(const std::vector<Vec3>& points, int rows, int columns,
                         const Vec3& into_specimen) {
  constexpr const char* fn = "grid_normals";
  if (rows < 2 || columns < 2) fail(fn, "the grid needs at least 2 rows and 2 columns");
  if (points.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(columns)) {
    fail(fn, std::to_string(points.size()) + " points for a " + std::to_string(rows) + " x " +
                 std::to_string(columns) + " grid");
  }
  for (const Vec3& p : points) require_finite(fn, "a grid point", p);
  const Vec3 z = unit_direction(fn, "the specimen's z", into_specimen);
  auto at = [&](int r, int c) -> const Vec3& {
    return points[static_cast<std::size_t>(r) * static_cast<std::size_t>(columns) +
                  static_cast<std::size_t>(c)];
  };
  // Derivative along one grid index (per grid step): central inside, one-sided at the edges.
  auto derivative = [](auto&& p, int k, int n) -> Vec3 {
    if (k > 0 && k < n - 1) return 0.5 * (p(k + 1) - p(k - 1));
    if (n == 2) return p(1) - p(0);
    if (k == 0) return 0.5 * (-3.0 * p(0) + 4.0 * p(1) - p(2));
    return 0.5 * (3.0 * p(n - 1) - 4.0 * p(n - 2) + p(n - 3));
  };
  GridNormals out;
  out.normal.reserve(points.size());
  out.tilt_rad.reserve(points.size());
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const Vec3 t_col = derivative([&](int k) { return at(r, k); }, c, columns);
      const Vec3 t_row = derivative([&](int k) { return at(k, c); }, r, rows);
      const Vec3 cross = t_col.cross(t_row);
      if (!(cross.norm() > 1e-12 * t_col.norm() * t_row.norm())) {
        fail(fn, "degenerate neighbourhood at row " + std::to_string(r + 1) + ", column " +
                     std::to_string(c + 1) + " (repeated or collinear points)");
      }
      Vec3 n = cross.normalized();
      if (n.dot(z) < 0.0) n = -n;
      out.normal.push_back(n);
      out.tilt_rad.push_back(angle_between(n, z));
    }
  }
  return out;
}

TracedSurface trace_surface(const std::vector<ApproachAtRest>& approaches, int rows, int columns,
                            const IndentationSource& source, double tip_radius_m,
                            const Vec3& into_specimen, int passes) {
  if (passes < 1) fail("trace_surface", "passes must be >= 1");
  if (approaches.size() != static_cast<std::size_t>(std::max(rows, 0)) *
                               static_cast<std::size_t>(std::max(columns, 0))) {
    fail("trace_surface", std::to_string(approaches.size()) + " approaches for a " +
                              std::to_string(rows) + " x " + std::to_string(columns) + " grid");
  }
  TracedSurface out;
  out.normal.reserve(approaches.size());
  for (const ApproachAtRest& a : approaches) out.normal.push_back(a.approach_dir.normalized());
  std::vector<Vec3> pts(approaches.size());
  for (int pass = 0; pass < passes; ++pass) {
    out.contact.clear();
    for (std::size_t k = 0; k < approaches.size(); ++k) {
      out.contact.push_back(contact_point(approaches[k], source, tip_radius_m, out.normal[k]));
      pts[k] = out.contact.back().point_m;
    }
    GridNormals g = grid_normals(pts, rows, columns, into_specimen);
    out.normal = std::move(g.normal);
    out.tilt_rad = std::move(g.tilt_rad);
  }
  return out;
}

}  // namespace palp::analysis
