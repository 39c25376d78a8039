// SPDX-License-Identifier: Apache-2.0
// Surface analysis for a traced grid (issue 5): the work-object frame from a three-point
// touch-off, the zero-force contact point from a guarded approach, and the normals and tilts of
// the traced surface. Plain functions over Eigen vectors: no I/O, no device. SI (m, N, N/m, Pa).
//
// Work-object frame (docs/rig-and-plan.md): origin at the first touch-off point, x axis toward
// the second, z the normal of the plane of the three points, pointing INTO the specimen (the
// same side as the probe's approach direction), y = z x x. The third point only fixes the plane
// (either side of the x axis). In the simulated world the work object is the phantom frame.
//
// Contact point from a guarded approach that stopped at rest (all in the robot's base frame):
//   apex  = tcp + s dir                 the tip apex: TCP (apex at stroke origin) + coil stroke s
//   delta = 1.5 F / k_c                 Hertzian indentation from a measured contact stiffness,
//     or  = (3 F / (4 E* sqrt(R)))^(2/3)  from a stated E* (Hertz), or 0 when neither is given
//   apex0  = apex - delta dir           the apex at zero force
//   centre = apex0 - R dir              the tip sphere's centre
//   point  = centre + R n               the touched point, n the surface normal into the specimen
// F is the detection force k_v (s_free - s) the springs put on the contact.
//
// Normals on an n x m grid of points (row-major, rows along the work object's y, columns along
// its x): tangents by finite differences of the grid neighbours, central in the interior,
// second-order one-sided (-3 p0 + 4 p1 - p2) / 2 at the edges (two-point with only two rows or
// columns); normal = unit(t_column x t_row) turned into the specimen (n . z_wo > 0); tilt = the
// angle between n and the work object's z.
//
// Errors: bad input (non-finite values, zero or non-unit directions, wrong sizes, collinear
// touch-off points) throws palp::ConfigError with a message naming the function and the problem.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3
#include <optional>
#include <vector>

#include "palp/pose.hpp"

namespace palp::analysis {

using Vec3 = Eigen::Vector3d;

/// The work-object frame (as a Pose in the base frame, KUKA ZYX angles) from a three-point
/// touch-off: the origin, a point along +x, a third point in the plane off the x axis, and the
/// probe's approach direction (which side +z is on). ConfigError when the points coincide or are
/// collinear (the sine of the angle at the origin below 1e-6) or the approach lies in the plane.
Pose register_work_object(const Vec3& p_origin, const Vec3& p_on_x_axis, const Vec3& p_in_plane,
                          const Vec3& approach_dir);

/// A point given in a frame (a Pose in base) expressed in base, and back.
Vec3 frame_to_base(const Pose& frame, const Vec3& p_frame);
Vec3 base_to_frame(const Pose& frame, const Vec3& p_base);
/// The frame's z axis (unit) in base.
Vec3 frame_z_axis(const Pose& frame);

/// How to turn the detection force into the indentation it already made (Hertz, sphere).
/// E* wins when both are given; neither: no correction.
struct IndentationSource {
  std::optional<double> contact_stiffness_N_per_m;  ///< measured k_c = dF/d(delta) at F
  std::optional<double> e_star_Pa;                  ///< stated reduced modulus
};

/// Indentation under force_N (>= 0) of a sphere of radius tip_radius_m: 1.5 F / k_c, or
/// (3 F / (4 E* sqrt R))^(2/3), or 0. ConfigError on a negative force or non-positive k_c, E*, R.
double hertz_indentation_m(double force_N, const IndentationSource& source, double tip_radius_m);

/// A guarded approach that stopped and came to rest (base frame).
struct ApproachAtRest {
  Vec3 tcp_m = Vec3::Zero();               ///< TCP at rest: the tip apex at stroke origin
  Vec3 approach_dir = Vec3::UnitZ();       ///< unit, the direction of the approach
  double stroke_m = 0.0;                   ///< coil stroke position s at rest (apex = tcp + s dir)
  double detection_force_N = 0.0;          ///< k_v (s_free - s): the force on the contact
};

struct ContactPoint {
  Vec3 point_m = Vec3::Zero();             ///< the touched point on the surface, zero force
  Vec3 apex_zero_force_m = Vec3::Zero();   ///< where the apex was at first touch
  Vec3 sphere_centre_m = Vec3::Zero();
  double indentation_m = 0.0;              ///< delta removed along the approach
};

/// The zero-force contact point of one approach, given the surface normal n (unit, into the
/// specimen; n = approach_dir for a first estimate).
ContactPoint contact_point(const ApproachAtRest& at_rest, const IndentationSource& source,
                           double tip_radius_m, const Vec3& normal_into_specimen);

/// Normals (unit, into the specimen) and tilts (rad, to into_specimen) of an n x m grid.
struct GridNormals {
  std::vector<Vec3> normal;
  std::vector<double> tilt_rad;
};

/// points: rows x columns, row-major (points[r * columns + c]); into_specimen: the work
/// object's z in the same frame. ConfigError for fewer than 2 rows or columns, a size mismatch,
/// non-finite points or a degenerate neighbourhood (zero tangent, parallel tangents).
GridNormals grid_normals(const std::vector<Vec3>& points, int rows, int columns,
                         const Vec3& into_specimen);

/// A traced surface: contact points with their normals and tilts, row-major like the grid.
struct TracedSurface {
  std::vector<ContactPoint> contact;
  std::vector<Vec3> normal;
  std::vector<double> tilt_rad;
};

/// Contact points <-> normals: start with n = approach_dir at every point, then `passes` times
/// compute the contact points with the current normals and the normals from those points
/// (the returned normals and tilts are the stencil on the returned points). ConfigError as for
/// contact_point and grid_normals, or passes < 1.
TracedSurface trace_surface(const std::vector<ApproachAtRest>& approaches, int rows, int columns,
                            const IndentationSource& source, double tip_radius_m,
                            const Vec3& into_specimen, int passes = 3);

}  // namespace palp::analysis
