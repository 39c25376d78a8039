// SPDX-License-Identifier: Apache-2.0
// The spherical tip's first touch (sphere_touch, Plant's contact zero): on a plane tilted by
// theta the apex stops R (1/cos(theta) - 1) above the surface under it, and touches off-axis at
// the foot of the normal through the sphere's centre; flat tops are unchanged exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "palp/plant/pad_phantom.hpp"
#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;
constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SphereTouch, PlaneTiltedByThetaStopsTheApexRTimesSecantMinusOneAboveTheSurface) {
  const auto ph = load_shipped_phantom("plane_tilted_10");
  const double th = 10.0 * kDeg;
  for (const ProbeSite& s : {ph->grid_point(1, 1), ph->grid_point(5, 5), ph->grid_point(9, 7)}) {
    const SphereTouch t = sphere_touch(*ph, s.x_m, s.y_m, kR);
    ASSERT_TRUE(t.touches);
    const double expected = ph->surface_z_m(s.x_m, s.y_m) - kR * (1.0 / std::cos(th) - 1.0);
    EXPECT_NEAR(t.apex_z_m, expected, 0.1e-6);
    // The touched point: R sin(theta) toward -x (up the slope), on the surface, and the normal
    // (-sin, 0, cos) into the specimen.
    EXPECT_NEAR(t.point_x_m, s.x_m - kR * std::sin(th), 1e-8);
    EXPECT_NEAR(t.point_y_m, s.y_m, 1e-8);
    EXPECT_NEAR(t.point_z_m, ph->surface_z_m(t.point_x_m, t.point_y_m), 1e-15);
    EXPECT_NEAR(t.normal[0], -std::sin(th), 1e-6);
    EXPECT_NEAR(t.normal[1], 0.0, 1e-6);
    EXPECT_NEAR(t.normal[2], std::cos(th), 1e-6);
  }
}

TEST(SphereTouch, ShallowAndSteepTiltsFollowTheSecantLaw) {
  for (double deg : {1.0, 5.0, 20.0, 30.0, -15.0}) {
    PadPhantomSpec spec = std::static_pointer_cast<const PadPhantom>(
                              load_shipped_phantom("plane_tilted_10"))->spec();
    spec.surface_tilt_about_y_rad = deg * kDeg;
    spec.thickness_m = 0.1;  // room for the steeper wedges' channels
    spec.deep.depth_m = 0.06;
    const PadPhantom ph(spec);
    const double x = 0.05, y = 0.045;
    const SphereTouch t = sphere_touch(ph, x, y, kR);
    EXPECT_NEAR(t.apex_z_m, ph.surface_z_m(x, y) - kR * (1.0 / std::cos(deg * kDeg) - 1.0),
                0.1e-6)
        << deg << " degrees";
  }
}

TEST(SphereTouch, FlatTopsAreUnchangedExactly) {
  for (const char* name : {"solid_1d", "hollow_1d", "insert_1d"}) {
    const auto ph = load_shipped_phantom(name);
    for (const ProbeSite& s : ph->sites()) {
      const SphereTouch t = sphere_touch(*ph, s.x_m, s.y_m, kR);
      EXPECT_EQ(t.apex_z_m, ph->surface_z_m(s.x_m, s.y_m)) << name;
      EXPECT_EQ(t.point_x_m, s.x_m);
      EXPECT_EQ(t.point_y_m, s.y_m);
      EXPECT_EQ(t.normal[2], 1.0);
    }
  }
}

TEST(SphereTouch, SteepPadWaveTouchesWhereTheNormalPassesThroughTheCentre) {
  const auto ph = load_shipped_phantom("pad_2d_steep");
  const auto& spec = std::static_pointer_cast<const PadPhantom>(ph)->spec();
  const double k = 2.0 * std::numbers::pi / spec.wave_length_m;
  EXPECT_NEAR(spec.wave_amplitude_m * k, std::tan(15.0 * kDeg), 1e-12);  // steepest slope 15 deg
  for (const ProbeSite& s : ph->sites()) {
    if (s.column != 5) continue;
    const SphereTouch t = sphere_touch(*ph, s.x_m, s.y_m, kR);
    // The touched point lies on the surface, the sphere's centre along its normal at distance R.
    const double slope = spec.wave_amplitude_m * k * std::cos(k * t.point_y_m);
    const double len = std::hypot(1.0, slope);
    EXPECT_NEAR(t.normal[1], -slope / len, 1e-6) << "row " << s.row;
    EXPECT_NEAR(t.normal[2], 1.0 / len, 1e-6);
    EXPECT_NEAR(t.point_z_m - kR * t.normal[2], t.apex_z_m - kR, 1e-9);
    EXPECT_LE(t.apex_z_m, ph->surface_z_m(s.x_m, s.y_m));
    // Never more than R (1/cos 15 - 1) = 88 um above the surface under the apex.
    EXPECT_GE(t.apex_z_m, ph->surface_z_m(s.x_m, s.y_m) - kR * (1.0 / std::cos(15 * kDeg) - 1.0)
                              - 1e-9);
  }
}

TEST(SphereTouch, PlantContactStartsAtTheSphereTouchOnASlope) {
  const auto ph = load_shipped_phantom("plane_tilted_10");
  PlantConfig cfg;
  Plant p(cfg, ph);
  const ProbeSite s = ph->grid_point(5, 5);
  const double sf = cfg.mechanics.float_position_m;
  const double z_touch = sphere_touch(*ph, s.x_m, s.y_m, kR).apex_z_m;
  p.set_mount(s.x_m, s.y_m, z_touch - sf - 1e-6);  // 1 um short of the touch
  p.reset_state({sf, 0.0, 0.5});
  EXPECT_EQ(p.contact_force_N(), 0.0);
  p.set_mount(s.x_m, s.y_m, z_touch - sf + 10e-6);  // 10 um past it
  EXPECT_NEAR(p.indentation_m(), 10e-6, 1e-12);
  EXPECT_GT(p.contact_force_N(), 0.0);
  EXPECT_NEAR(p.site_touch().apex_z_m, z_touch, 0.0);
  EXPECT_NEAR(p.site_touch().normal[0], -std::sin(10 * kDeg), 1e-6);
}

TEST(SphereTouch, SubMicrometreMovesFollowTheTangentPlaneWithin0p1Nanometre) {
  const auto ph = load_shipped_phantom("pad_2d_steep");
  PlantConfig cfg;
  Plant p(cfg, ph);
  const ProbeSite s = ph->grid_point(2, 4);
  const double z = sphere_touch(*ph, s.x_m, s.y_m, kR).apex_z_m - cfg.mechanics.float_position_m;
  p.set_mount(s.x_m, s.y_m, z);
  for (const double d : {0.3e-6, -0.9e-6, 5e-6}) {  // the last one is searched afresh
    p.move_mount(s.x_m + 0.5 * d, s.y_m + d, z);
    p.step(0.0);
    const SphereTouch fresh = sphere_touch(*ph, s.x_m + 0.5 * d, s.y_m + d, kR);
    EXPECT_NEAR(p.site_touch().apex_z_m, fresh.apex_z_m, 1e-10) << d;
    EXPECT_NEAR(p.site_touch().point_y_m, fresh.point_y_m, 1e-8) << d;
  }
}

TEST(SphereTouch, OffThePhantomNothingTouches) {
  const auto ph = load_shipped_phantom("pad_2d");
  const SphereTouch t = sphere_touch(*ph, 0.5, 0.5, kR);
  EXPECT_FALSE(t.touches);
  EXPECT_TRUE(std::isinf(t.apex_z_m));
  EXPECT_THROW(sphere_touch(*ph, 0.05, 0.05, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace palp::plant
