// SPDX-License-Identifier: Apache-2.0
// finish_surface: the contact points, normals and tilts of a traced surface from what was
// measured at rest, with the surface analysis's functions (analysis/surface.hpp).
#include <cmath>

#include "palp/analysis/surface.hpp"
#include "palp/trace.hpp"
#include "toucher.hpp"

namespace palp {

namespace detail {
analysis::ApproachAtRest approach_at_rest(const TracePoint& m) {
  analysis::ApproachAtRest a;
  a.tcp_m = analysis::Vec3(m.tcp_at_rest.x_m, m.tcp_at_rest.y_m, m.tcp_at_rest.z_m);
  const proto::rb::Transform t = transform_of(m.tcp_at_rest);
  a.approach_dir = analysis::Vec3(t.r.m[0][2], t.r.m[1][2], t.r.m[2][2]);
  a.stroke_m = m.stroke_at_rest_m;
  a.detection_force_N = m.detection_force_N;
  return a;
}
}  // namespace detail

void finish_surface(TracedSurface& s) {
  using analysis::Vec3;
  const std::size_t total = static_cast<std::size_t>(s.rows) * static_cast<std::size_t>(s.columns);
  bool grid = s.rows >= 2 && s.columns >= 2 && s.points.size() == total;
  // the whole grid, row-major (an adaptive map that measured every point has them in its order)
  for (std::size_t k = 0; grid && k < s.points.size(); ++k)
    grid = s.points[k].ok && s.points[k].row == static_cast<int>(k) / s.columns + 1 &&
           s.points[k].column == static_cast<int>(k) % s.columns + 1;
  const Vec3 wo_z = analysis::frame_z_axis(s.work_object);

  std::vector<analysis::ApproachAtRest> at(s.points.size());
  std::vector<analysis::IndentationSource> src(s.points.size());
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    if (!s.points[k].ok) continue;
    at[k] = detail::approach_at_rest(s.points[k]);
    src[k].e_star_Pa = s.contact_E_star_Pa;
    src[k].contact_stiffness_N_per_m = s.points[k].contact_stiffness_N_per_m;
  }
  // normals start as the approach axis; with a whole grid, 3 passes of points <-> normals
  std::vector<Vec3> normal(s.points.size());
  for (std::size_t k = 0; k < s.points.size(); ++k) normal[k] = at[k].approach_dir;
  std::vector<analysis::ContactPoint> cp(s.points.size());
  std::vector<double> tilt(s.points.size(), 0.0);
  const int passes = grid ? 3 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Vec3> pts(s.points.size(), Vec3::Zero());
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      if (!s.points[k].ok) continue;
      cp[k] = analysis::contact_point(at[k], src[k], s.tip_radius_m, normal[k]);
      pts[k] = cp[k].point_m;
    }
    if (!grid) break;
    const analysis::GridNormals g = analysis::grid_normals(pts, s.rows, s.columns, wo_z);
    normal = g.normal;
    tilt = g.tilt_rad;
  }
  if (grid) {  // the points with the final normals
    for (std::size_t k = 0; k < s.points.size(); ++k)
      cp[k] = analysis::contact_point(at[k], src[k], s.tip_radius_m, normal[k]);
  }
  s.normals_from_grid = grid;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    TracePoint& p = s.points[k];
    if (!p.ok) continue;
    const Vec3 c = analysis::base_to_frame(s.work_object, cp[k].point_m);
    const Vec3 a = analysis::base_to_frame(s.work_object, cp[k].apex_zero_force_m);
    const Vec3 n = analysis::base_to_frame(s.work_object, normal[k]) -
                   analysis::base_to_frame(s.work_object, Vec3::Zero());  // a direction
    p.x_m = c.x(), p.y_m = c.y(), p.z_m = c.z();
    p.apex_x_m = a.x(), p.apex_y_m = a.y(), p.apex_z_m = a.z();
    for (int i = 0; i < 3; ++i) p.normal[i] = n[i];
    p.tilt_rad = grid ? tilt[k] : std::acos(std::min(1.0, std::abs(normal[k].dot(wo_z))));
    p.indentation_m = cp[k].indentation_m;
  }
}

}  // namespace palp
