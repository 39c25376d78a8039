// SPDX-License-Identifier: Apache-2.0
// Surface analysis with known truth: exact plane normals, a sphere, the stencil on a 15-degree
// sine, a touch-off on a rotated and translated frame, the contact point of a sphere tip on a
// 10-degree plane, the indentation formulas against hand values, and one-line errors.
#include "palp/analysis/surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <numbers>

#include "palp/error.hpp"

namespace palp::analysis {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kR = 2.5e-3;

// A work-object frame well away from identity: rotated about all three axes, translated.
Pose odd_frame() {
  Pose f;
  f.x_m = 0.512;
  f.y_m = -0.231;
  f.z_m = 0.307;
  f.a_rad = 37.0 * kDeg;
  f.b_rad = -12.0 * kDeg;
  f.c_rad = 171.0 * kDeg;  // z of the frame points roughly down in base
  return f;
}

std::string config_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Surface, TouchOffRecoversARotatedTranslatedFrameTo1e12) {
  const Pose truth = odd_frame();
  const Vec3 o = frame_to_base(truth, Vec3(0, 0, 0));
  const Vec3 px = frame_to_base(truth, Vec3(0.030, 0, 0));
  const Vec3 dir = frame_z_axis(truth);
  for (double side : {1.0, -1.0}) {  // the third point on either side of the x axis
    const Vec3 p3 = frame_to_base(truth, Vec3(0.011, side * 0.020, 0));
    const Pose got = register_work_object(o, px, p3, dir);
    for (const Vec3& q : {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, 0, 0.1)}) {
      EXPECT_LT((frame_to_base(got, q) - frame_to_base(truth, q)).norm(), 1e-12);
    }
    EXPECT_LT((base_to_frame(got, px) - Vec3(0.030, 0, 0)).norm(), 1e-12);
  }
}

TEST(Surface, TouchOffTurnsZIntoTheSpecimenAlongTheApproach) {
  // Points in the base xy plane, the probe approaching along base -z: the frame's z is -z_base.
  const Pose got = register_work_object(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                        Vec3(0, 0, -1));
  EXPECT_LT((frame_z_axis(got) - Vec3(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((frame_to_base(got, Vec3(0, 1, 0)) - Vec3(0, -1, 0)).norm(), 1e-15);  // y = z x x
}

TEST(Surface, TouchOffRejectsCollinearOrCoincidentPointsWithOneLine) {
  const Vec3 dir(0, 0, 1);
  EXPECT_EQ(config_error([&] {
              register_work_object(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1e-9, 0), dir);
            }),
            "register_work_object: the three points are collinear: they do not define a plane");
  EXPECT_EQ(config_error([&] {
              register_work_object(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(0, 1, 0), dir);
            }),
            "register_work_object: the origin and the point on the x axis coincide");
  EXPECT_EQ(config_error([&] {
              register_work_object(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0));
            }),
            "register_work_object: the approach direction lies in the plane of the points");
}

TEST(Surface, TiltedPlaneNormalsAreExactTo1e9Rad) {
  const Pose wo = odd_frame();
  const Vec3 z_wo = frame_z_axis(wo);
  // Plane z = tan(10 deg) x + tan(4 deg) y in the work object, 7 x 5 points, 10 x 8 mm pitch.
  const double gx = std::tan(10 * kDeg), gy = std::tan(4 * kDeg);
  std::vector<Vec3> pts;
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 5; ++c) {
      const double x = 0.01 * c, y = 0.008 * r;
      pts.push_back(frame_to_base(wo, Vec3(x, y, gx * x + gy * y + 0.002)));
    }
  const GridNormals g = grid_normals(pts, 7, 5, z_wo);
  const Vec3 truth_wo = Vec3(-gx, -gy, 1.0).normalized();
  const Vec3 truth = frame_to_base(wo, truth_wo) - frame_to_base(wo, Vec3::Zero());
  const double tilt = std::atan(std::hypot(gx, gy));
  for (std::size_t k = 0; k < pts.size(); ++k) {
    EXPECT_LT(std::atan2(g.normal[k].cross(truth).norm(), g.normal[k].dot(truth)), 1e-9) << k;
    EXPECT_NEAR(g.tilt_rad[k], tilt, 1e-9) << k;
  }
}

TEST(Surface, SphereNormalsPointRadiallyAndExactlyAtTheSymmetricCentre) {
  // Cap of a 50 mm sphere (centre above the surface, -z), 5 x 5 points at 4 mm pitch.
  const double rs = 0.05;
  const Vec3 centre(0, 0, 0);
  std::vector<Vec3> pts;
  for (int r = -2; r <= 2; ++r)
    for (int c = -2; c <= 2; ++c) {
      const double x = 0.004 * c, y = 0.004 * r;
      pts.push_back(Vec3(x, y, std::sqrt(rs * rs - x * x - y * y)));
    }
  const GridNormals g = grid_normals(pts, 5, 5, Vec3::UnitZ());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Vec3 radial = (pts[k] - centre).normalized();
    EXPECT_LT(std::acos(std::min(1.0, g.normal[k].dot(radial))), 1e-3) << k;  // < 0.06 deg
  }
  EXPECT_LT((g.normal[12] - Vec3::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(g.tilt_rad[12], 0.0, 1e-15);
  // Central differences on the cap: the tilt of row 3, column 4 is atan of the secant slope.
  const double z1 = pts[13 + 1].z(), z0 = pts[13 - 1].z();
  EXPECT_NEAR(g.tilt_rad[13], std::atan(std::abs(z1 - z0) / (2 * 0.004)), 1e-12);
}

TEST(Surface, FifteenDegreeSineOnA9x9GridMatchesTheStencilByHand) {
  const double a = 1.5e-3, lambda = 2 * std::numbers::pi * a / std::tan(15 * kDeg);
  const double k = 2 * std::numbers::pi / lambda, h = 0.01;
  auto z = [&](int r) { return a * std::sin(k * (0.005 + h * r)); };
  std::vector<Vec3> pts;
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) pts.push_back(Vec3(0.01 + h * c, 0.005 + h * r, z(r)));
  const GridNormals g = grid_normals(pts, 9, 9, Vec3::UnitZ());
  for (int r = 0; r < 9; ++r) {
    double dz;  // height change per grid step along the rows, as the stencil takes it
    if (r == 0) dz = 0.5 * (-3 * z(0) + 4 * z(1) - z(2));
    else if (r == 8) dz = 0.5 * (3 * z(8) - 4 * z(7) + z(6));
    else dz = 0.5 * (z(r + 1) - z(r - 1));
    const Vec3 expected = Vec3(0, -dz, h).normalized();
    for (int c = 0; c < 9; ++c) {
      const std::size_t i = static_cast<std::size_t>(r * 9 + c);
      EXPECT_LT((g.normal[i] - expected).norm(), 1e-12) << r << "," << c;
      EXPECT_NEAR(g.tilt_rad[i], std::atan(std::abs(dz) / h), 1e-12);
    }
  }
  // Inside, the stencil is the slope times sin(kh)/(kh): 10 mm is coarse for a 35 mm wave.
  EXPECT_NEAR(0.5 * (z(5) - z(3)) / h, a * k * std::cos(k * (0.005 + 4 * h)) * std::sin(k * h) / (k * h),
              1e-15);
}

TEST(Surface, HertzIndentationMatchesHandValues) {
  // (3 x 9 mN / (4 x 3.3 MPa x sqrt(2.5 mm)))^(2/3) = 11.8726 um; 1.5 x 8.78 mN / 500 N/m.
  EXPECT_NEAR(hertz_indentation_m(0.009, {std::nullopt, 3.3e6}, kR), 1.1872619578873113e-05,
              1e-18);
  EXPECT_NEAR(hertz_indentation_m(0.00878, {500.0, std::nullopt}, kR), 2.634e-05, 1e-18);
  EXPECT_NEAR(hertz_indentation_m(0.009, {500.0, 3.3e6}, kR), 1.1872619578873113e-05, 1e-18);
  EXPECT_EQ(hertz_indentation_m(0.009, {}, kR), 0.0);
  // Consistency: the Hertz stiffness at F, 2 E* sqrt(R delta), gives back the same delta.
  const double d = hertz_indentation_m(0.009, {std::nullopt, 3.3e6}, kR);
  const double kc = 2 * 3.3e6 * std::sqrt(kR * d);
  EXPECT_NEAR(hertz_indentation_m(0.009, {kc, std::nullopt}, kR), d, 1e-15);
  EXPECT_EQ(config_error([] { hertz_indentation_m(-1.0, {}, kR); }),
            "hertz_indentation_m: the force must be finite and >= 0 N");
  EXPECT_EQ(config_error([] { hertz_indentation_m(0.01, {0.0, std::nullopt}, kR); }),
            "hertz_indentation_m: the contact stiffness must be positive");
}

// An approach at rest onto the plane z = tan(theta) x (+z into the specimen), approach +z,
// built from the sphere's first-touch geometry (apex touches R (1/cos - 1) above the surface)
// and a Hertz indentation with E*.
ApproachAtRest approach_onto_tilted_plane(double x, double y, double theta, double e_star,
                                          double force) {
  const double apex_touch = std::tan(theta) * x - kR * (1.0 / std::cos(theta) - 1.0);
  const double delta = std::pow(3 * force / (4 * e_star * std::sqrt(kR)), 2.0 / 3.0);
  ApproachAtRest a;
  a.stroke_m = 0.025;
  a.tcp_m = Vec3(x, y, apex_touch + delta - a.stroke_m);
  a.approach_dir = Vec3::UnitZ();
  a.detection_force_N = force;
  return a;
}

TEST(Surface, ContactPointOfASphereTipOnA10DegreePlaneLandsOnThePlane) {
  const double th = 10 * kDeg;
  const Vec3 n(-std::sin(th), 0, std::cos(th));
  const ApproachAtRest a = approach_onto_tilted_plane(0.03, 0.02, th, 3.3e6, 0.00878);
  const ContactPoint p = contact_point(a, {std::nullopt, 3.3e6}, kR, n);
  const double off_plane = (p.point_m.z() - std::tan(th) * p.point_m.x()) * std::cos(th);
  EXPECT_LT(std::abs(off_plane), 0.1e-6);
  EXPECT_NEAR(p.point_m.x(), 0.03 - kR * std::sin(th), 1e-12);  // R sin(theta) up the slope
  // Without the normal (n = dir) the point is the apex at zero force: 38 um above the plane.
  const ContactPoint q = contact_point(a, {std::nullopt, 3.3e6}, kR, Vec3::UnitZ());
  EXPECT_NEAR(std::tan(th) * q.point_m.x() - q.point_m.z(), kR * (1 / std::cos(th) - 1), 1e-12);
}

TEST(Surface, TraceOfA10DegreePlaneConvergesToThePlaneAndItsNormal) {
  const double th = 10 * kDeg;
  std::vector<ApproachAtRest> at_rest;
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c)
      at_rest.push_back(approach_onto_tilted_plane(0.01 + 0.01 * c, 0.005 + 0.01 * r, th, 3.3e6,
                                                   0.00878));
  const TracedSurface t = trace_surface(at_rest, 9, 9, {std::nullopt, 3.3e6}, kR, Vec3::UnitZ());
  const Vec3 n(-std::sin(th), 0, std::cos(th));
  for (std::size_t k = 0; k < at_rest.size(); ++k) {
    const Vec3& p = t.contact[k].point_m;
    EXPECT_LT(std::abs((p.z() - std::tan(th) * p.x()) * std::cos(th)), 1e-9) << k;
    EXPECT_LT((t.normal[k] - n).norm(), 1e-9) << k;
    EXPECT_NEAR(t.tilt_rad[k], th, 1e-9);
  }
}

TEST(Surface, BadGridsAndDirectionsGiveOneLineErrors) {
  std::vector<Vec3> pts(6, Vec3::Zero());
  EXPECT_EQ(config_error([&] { grid_normals(pts, 2, 2, Vec3::UnitZ()); }),
            "grid_normals: 6 points for a 2 x 2 grid");
  EXPECT_EQ(config_error([&] { grid_normals(pts, 1, 6, Vec3::UnitZ()); }),
            "grid_normals: the grid needs at least 2 rows and 2 columns");
  EXPECT_EQ(config_error([&] { grid_normals(pts, 2, 3, Vec3::UnitZ()); }),
            "grid_normals: degenerate neighbourhood at row 1, column 1 (repeated or collinear "
            "points)");
  ApproachAtRest a;
  a.approach_dir = Vec3(0, 0, 2);
  EXPECT_EQ(config_error([&] { contact_point(a, {}, kR, Vec3::UnitZ()); }),
            "contact_point: the approach direction must be a unit vector");
  a.approach_dir = Vec3::UnitZ();
  EXPECT_EQ(config_error([&] { contact_point(a, {}, kR, Vec3(0, 0, -1)); }),
            "contact_point: the normal must point into the specimen (n . dir > 0)");
}

}  // namespace
}  // namespace palp::analysis
