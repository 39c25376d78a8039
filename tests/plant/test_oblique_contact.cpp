// SPDX-License-Identifier: Apache-2.0
// The oblique contact (README.md "Oblique contact"): a sphere pressed along an axis at theta to
// the surface normal feels the normal law at delta cos(theta) plus Mindlin's tangential force
// (Johnson 1985 §7.5) limited by Coulomb friction. Pure-law tests against the closed forms; the
// sphere's first touch along a tilted axis; quasi-static ramps on the plant measuring the
// stiffness a vertical probe sees on tilted pads and an aligned probe sees on the wedge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "palp/plant/plant.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kRho = 2.0 / 3.0;  // Mindlin's k_t / k_n at nu = 0.5

ContactParams hertz_half_space() {
  ContactParams p;
  p.law = ContactLaw::hertz;
  p.e_star_Pa = 125.8e3;
  return p;
}

ContactParams pad_like() {  // Sneddon on a 20 mm layer with a series spring (the pad's law)
  ContactParams p;
  p.law = ContactLaw::sneddon;
  p.e_star_Pa = 3.3e6;
  p.layer_thickness_m = 0.020;
  p.structural_compliance_m_per_N = 1.25e-4;
  return p;
}

TEST(ObliqueContact, MindlinStiffnessRatioIsTwoThirdsForAnIncompressibleMaterial) {
  EXPECT_DOUBLE_EQ(mindlin_stiffness_ratio(kPoissonRatio), kRho);
  EXPECT_DOUBLE_EQ(mindlin_stiffness_ratio(0.0), 1.0);           // 8 G a / 2 against 2 (2 G) a
  EXPECT_NEAR(mindlin_stiffness_ratio(0.3), 1.4 / 1.7, 1e-15);
}

TEST(ObliqueContact, AnAxisAlongTheNormalIsTheNormalLawBitForBit) {
  const ObliqueSplit s = oblique_split(1.0, 0.5);
  EXPECT_EQ(s.cos_theta, 1.0);
  EXPECT_EQ(s.sin_theta, 0.0);
  EXPECT_EQ(s.axial_per_normal, 1.0);
  EXPECT_EQ(s.tangential_per_normal, 0.0);
  for (const ContactParams& p : {hertz_half_space(), pad_like()}) {
    for (double d = 1e-5; d < 3e-3; d *= 1.7) {
      const ElasticPoint a = oblique_elastic_contact(p, kR, d, 1.0), b = elastic_contact(p, kR, d);
      EXPECT_EQ(a.force_N, b.force_N) << d;
      EXPECT_EQ(a.stiffness_N_per_m, b.stiffness_N_per_m) << d;
    }
  }
  // the per-step model with its memory (standard linear solid, series spring)
  ContactParams p = pad_like();
  p.viscoelasticity = Viscoelasticity::standard_linear_solid;
  p.sls_relaxation_time_s = 0.05;
  p.sls_strength = 0.3;
  p.retardation_time_s = 2e-3;
  ContactModel with_cos, without;
  for (int k = 0; k < 400; ++k) {
    const double d = 1e-3 * std::sin(0.01 * k), rate = 0.2 * std::cos(0.01 * k);
    const auto a = with_cos.evaluate(p, kR, d, rate, 50e-6, 1.0);
    const auto b = without.evaluate(p, kR, d, rate, 50e-6);
    ASSERT_EQ(a.force_N, b.force_N) << k;
    ASSERT_EQ(a.stiffness_N_per_m, b.stiffness_N_per_m) << k;
    ASSERT_EQ(a.damping_N_s_per_m, b.damping_N_s_per_m) << k;
    ASSERT_EQ(a.rate_free_force_N, b.rate_free_force_N) << k;
  }
}

TEST(ObliqueContact, HertzHalfSpaceAt20DegreesIsTheClosedForm) {
  const ContactParams p = hertz_half_space();
  const double th = 20.0 * kDeg, c = std::cos(th), s = std::sin(th), t = std::tan(th);
  const double e = p.e_star_Pa;
  for (double d = 1e-5; d < 4e-3; d *= 1.3) {
    // F_axis = 4/3 E* sqrt(R) (delta cos)^1.5 (cos + rho sin tan); k = dF/d(delta)
    const double f = 4.0 / 3.0 * e * std::sqrt(kR) * std::pow(d * c, 1.5) * (c + kRho * s * t);
    const double k = 2.0 * e * std::sqrt(kR) * std::sqrt(d * c) * c * (c + kRho * s * t);
    const ElasticPoint o = oblique_elastic_contact(p, kR, d, c);
    EXPECT_NEAR(o.force_N / f - 1.0, 0.0, 1e-9) << d;
    EXPECT_NEAR(o.stiffness_N_per_m / k - 1.0, 0.0, 1e-9) << d;
    // the axial stiffness is the normal one at delta cos times cos^2 + rho sin^2
    const double kn = hertz_sphere(e, kR, d * c).stiffness_N_per_m;
    EXPECT_NEAR(o.stiffness_N_per_m / (kn * (c * c + kRho * s * s)) - 1.0, 0.0, 1e-12) << d;
  }
  EXPECT_FALSE(oblique_split(c, p.friction_coefficient).sliding);  // 2/3 tan 20 = 0.24 < 0.5
}

TEST(ObliqueContact, TheFrictionLimitSwitchesWhereRhoTanThetaEqualsMu) {
  for (const double mu : {0.3, 0.5}) {
    const double th_switch = std::atan(mu / kRho);  // 24.2 and 36.9 degrees
    const ObliqueSplit below = oblique_split(std::cos(th_switch - 1e-6), mu);
    const ObliqueSplit above = oblique_split(std::cos(th_switch + 1e-6), mu);
    EXPECT_FALSE(below.sliding) << mu;
    EXPECT_TRUE(above.sliding) << mu;
    EXPECT_NEAR(below.tangential_per_normal, kRho * std::tan(th_switch - 1e-6), 1e-12);
    EXPECT_EQ(above.tangential_per_normal, mu);
    EXPECT_NEAR(below.axial_per_normal, above.axial_per_normal, 1e-5);  // continuous
  }
  // sliding: the axial stiffness is k_n(delta cos) cos (cos + mu sin)
  ContactParams p = hertz_half_space();
  p.friction_coefficient = 0.2;
  const double th = 30.0 * kDeg, c = std::cos(th), s = std::sin(th);
  const double kn = hertz_sphere(p.e_star_Pa, kR, 1e-3 * c).stiffness_N_per_m;
  EXPECT_NEAR(oblique_elastic_contact(p, kR, 1e-3, c).stiffness_N_per_m / (kn * c * (c + 0.2 * s)),
              1.0, 1e-12);
}

TEST(ObliqueContact, AxialAndLateralForcesRecomposeTheNormalAndTangentialOnes) {
  for (const double deg : {5.0, 20.0, 40.0}) {
    const ObliqueSplit s = oblique_split(std::cos(deg * kDeg), 0.5);
    const double ft = s.tangential_per_normal;
    const double axial = s.axial_per_normal, lateral = s.lateral_per_normal;
    EXPECT_NEAR(axial * axial + lateral * lateral, 1.0 + ft * ft, 1e-12)
        << deg;
    if (!s.sliding) {
      EXPECT_NEAR(s.lateral_per_normal, s.sin_theta * (1.0 - kRho), 1e-12) << deg;
    }
  }
}

TEST(ObliqueContact, FrictionIsAnOptionalPhantomKeyThatReachesTheContactLaw) {
  EXPECT_EQ(load_shipped_phantom("wedge_25")->friction_coefficient(), 0.5);  // the default
  std::string text(shipped_phantom_text("wedge_25"));
  text += "friction_coefficient = 0.3\n";
  const auto ph = parse_phantom(text, "wedge_mu.phantom");
  EXPECT_EQ(ph->friction_coefficient(), 0.3);
  Plant plant(PlantConfig{}, ph);
  plant.set_mount(0.05, 0.035, -0.03);
  EXPECT_EQ(plant.contact_params().friction_coefficient, 0.3);
  try {
    parse_phantom(std::string(shipped_phantom_text("wedge_0")) + "friction_coefficient = -1\n",
                  "bad.phantom");
    FAIL() << "no error";
  } catch (const PhantomError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.phantom:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("friction_coefficient"), std::string::npos) << e.what();
  }
}

// --- the first touch along a tilted axis ------------------------------------------------------

std::shared_ptr<const Phantom> wedge(double tilt_deg) {
  std::string text(shipped_phantom_text("wedge_25"));
  const std::string key = "surface_tilt_about_y_deg = 25.0";
  text.replace(text.find(key), key.size(),
               "surface_tilt_about_y_deg = " + std::to_string(tilt_deg));
  return parse_phantom(text, "wedge_" + std::to_string(tilt_deg));
}

std::array<double, 3> tilted_about_y(double deg) {
  return {std::sin(deg * kDeg), 0.0, std::cos(deg * kDeg)};
}

TEST(ObliqueContact, AVerticalAxisTouchesExactlyAsSphereTouch) {
  const auto ph = load_shipped_phantom("pad_2d_steep");
  const SphereTouch a = sphere_touch_along(*ph, 0.031, 0.042, {0.0, 0.0, 1.0}, kR);
  const SphereTouch b = sphere_touch(*ph, 0.031, 0.042, kR);
  EXPECT_EQ(a.apex_z_m, b.apex_z_m);
  EXPECT_EQ(a.point_y_m, b.point_y_m);
  EXPECT_EQ(a.normal, b.normal);
}

TEST(ObliqueContact, AnAxisTiltedByAlphaTouchesAFlatTopROneMinusCosAlphaEarly) {
  const auto flat = load_shipped_phantom("wedge_0");
  for (const double alpha : {10.0, 20.0, 35.0}) {
    const SphereTouch t = sphere_touch_along(*flat, 0.05, 0.045, tilted_about_y(alpha), kR);
    ASSERT_TRUE(t.touches);
    // the centre reaches z = -R; the apex sits R cos(alpha) below it
    EXPECT_NEAR(t.apex_z_m, -kR * (1.0 - std::cos(alpha * kDeg)), 1e-10) << alpha;
    EXPECT_NEAR(t.point_z_m, 0.0, 1e-12) << alpha;
    EXPECT_NEAR(t.normal[2], 1.0, 1e-9) << alpha;
  }
}

TEST(ObliqueContact, AnAxisAlongTheWedgesNormalTouchesWithTheApexOnTheSurface) {
  const auto w = load_shipped_phantom("wedge_25");
  const std::array<double, 3> n = tilted_about_y(-25.0);  // into the specimen, up the slope
  const double z_s = w->surface_z_m(0.05, 0.035);          // 0 at the tilt axis
  const SphereTouch t = sphere_touch_along(*w, 0.05, 0.035, n, kR);
  ASSERT_TRUE(t.touches);
  EXPECT_NEAR(t.apex_z_m, z_s, 1e-10);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(t.normal[i], n[i], 1e-7) << i;
}

TEST(ObliqueContact, ThePlantTakesTheObliqueLawAlongTheAxisAtTheTouchedNormal) {
  const auto tilted = load_shipped_phantom("plane_tilted_10");
  test::Rig rig{PlantConfig{}, tilted};
  const ProbeSite site = tilted->grid_point(4, 5);
  test::touch_at_float(rig, site.x_m, site.y_m);
  const double sf = rig.plant.config().mechanics.float_position_m;
  // theta from the sphere's touch (normal within ~1e-6 rad, README.md "Sphere tip")
  const double c = rig.plant.axis_normal_cosine();
  EXPECT_NEAR(c, std::cos(10 * kDeg), 1e-8);
  const ContactParams p = rig.plant.contact_params();
  for (const double d : {0.1e-3, 0.5e-3, 1.5e-3}) {
    rig.plant.reset_state({sf + d, 0.0, 1.0});  // at rest: no viscous part
    const double f = oblique_elastic_contact(p, kR, d, c).force_N;
    EXPECT_NEAR(rig.plant.contact_force_N() / f, 1.0, 1e-9) << d;
    const ObliqueSplit s = oblique_split(c, p.friction_coefficient);
    EXPECT_NEAR(rig.plant.normal_contact_force_N(), elastic_contact(p, kR, d * c).force_N, 1e-9);
    EXPECT_NEAR(rig.plant.tangential_contact_force_N(),
                rig.plant.normal_contact_force_N() * s.tangential_per_normal, 1e-12);
    // the force on the tip: against the axis by F_axis, across it by F_lat, down the slope
    const auto v = rig.plant.contact_force_vector_N();
    EXPECT_NEAR(-v[2], rig.plant.contact_force_N(), 1e-9);
    EXPECT_NEAR(v[0], rig.plant.normal_contact_force_N() * s.lateral_per_normal, 1e-9);
  }
}

// --- quasi-static ramps on the plant -----------------------------------------------------------

// A probe along `axis` at the surface point above (x, y): the tip just touches at the float
// position; the coil's weight along the axis follows the tilt. Staircase 0.5 A + 5 mA every
// 50 ms; depth from the encoder past the touch; force F_o = K_f (i - I_c) - k_v delta (the
// paper's, offset by the weight's change, which a slope does not see); k = the least-squares
// slope over depths 0.25-0.75 mm. The encoder's 1 um steps and the current noise scatter such
// a k by ~0.15 %, so ratios are held to 0.3 % (the effects are 1.2-7.4 %).
double ramp_k_N_per_m(std::shared_ptr<const Phantom> ph, double x, double y,
                      const std::array<double, 3>& axis) {
  test::Rig rig{PlantConfig{}, ph};
  Plant& p = rig.plant;
  const double sf = p.config().mechanics.float_position_m;
  p.set_probe_axis(axis);
  p.set_gravity_axis_cosine(axis[2]);  // the phantom's z is down
  const double z_s = ph->surface_z_m(x, y);
  const double x0 = x - z_s / axis[2] * axis[0], y0 = y - z_s / axis[2] * axis[1];
  const double apex_t = sphere_touch_along(*ph, x0, y0, axis, kR).apex_z_m / axis[2];
  p.set_mount(x0 + (apex_t - sf) * axis[0], y0 + (apex_t - sf) * axis[1], (apex_t - sf) * axis[2]);
  rig.start_at(sf, test::kIc);
  rig.run(test::kIc, 0.2);
  const double dt = p.config().tick_period_s;
  const auto n = static_cast<int>(std::lround(0.05 / dt));
  std::vector<double> depth, force;
  for (int k = 1; k < 1000; ++k) {
    const double i = test::kIc + 0.005 * k;
    double sum = 0.0;
    for (int t = 0; t < n; ++t) {
      rig.tick(i);
      sum += p.encoder_count() * p.config().sensors.encoder_resolution_m;
    }
    const double d = sum / n - sf;
    if (d > 0.8e-3) break;
    if (d < 0.25e-3 || d > 0.75e-3) continue;
    depth.push_back(d);
    force.push_back(test::kKf * (i - test::kIc) - test::kKv * d);
  }
  EXPECT_GT(depth.size(), 20u);
  return test::fit_line(depth, force).slope;
}

// The law's own prediction: the k_fd secant (0.25-0.75 mm) along the axis over the flat one.
double predicted_ratio(const ContactParams& p, double theta) {
  const double c = std::cos(theta);
  auto secant = [&](double cos_t) {
    return oblique_elastic_contact(p, kR, 0.75e-3, cos_t).force_N -
           oblique_elastic_contact(p, kR, 0.25e-3, cos_t).force_N;
  };
  return secant(c) / secant(1.0);
}

TEST(ObliqueContact, AVerticalProbeOnPlaneTilted10MeasuresTheFlatKTimesThePredictedFactor) {
  std::string text(shipped_phantom_text("plane_tilted_10"));
  const std::string key = "surface_tilt_about_y_deg = 10.0";
  text.replace(text.find(key), key.size(), "surface_tilt_about_y_deg = 0.0");
  const auto flat = parse_phantom(text, "plane_tilted_0");
  const auto tilted = load_shipped_phantom("plane_tilted_10");
  const ProbeSite site = tilted->grid_point(4, 5);  // x = 50 mm: the top at z = 0 in both
  const double k_flat = ramp_k_N_per_m(flat, site.x_m, site.y_m, {0, 0, 1});
  const double k_tilt = ramp_k_N_per_m(tilted, site.x_m, site.y_m, {0, 0, 1});
  const double predicted = predicted_ratio(tilted->contact_params(site.x_m, site.y_m), 10 * kDeg);
  std::printf("plane_tilted_10, row 4 column 5: k flat %.1f N/m, tilted %.1f N/m, ratio %.5f, "
              "predicted %.5f (cos^2 + rho sin^2 = %.5f)\n",
              k_flat, k_tilt, k_tilt / k_flat, predicted,
              std::pow(std::cos(10 * kDeg), 2) + kRho * std::pow(std::sin(10 * kDeg), 2));
  EXPECT_LT(k_tilt, k_flat * 0.995);
  EXPECT_NEAR(k_tilt / k_flat / predicted, 1.0, 3e-3);
}

TEST(ObliqueContact, UnalignedProbesOnWedgesLoseThePredictedStiffnessAndAlignedOnesDoNot) {
  const auto flat = load_shipped_phantom("wedge_0");
  const ProbeSite site = flat->grid_point(4, 5);
  const double k_flat = ramp_k_N_per_m(flat, site.x_m, site.y_m, {0, 0, 1});
  for (const double deg : {10.0, 15.0, 20.0, 25.0}) {
    const auto w = wedge(deg);
    const double k_vertical = ramp_k_N_per_m(w, site.x_m, site.y_m, {0, 0, 1});
    const double k_aligned = ramp_k_N_per_m(w, site.x_m, site.y_m, tilted_about_y(-deg));
    const double predicted = predicted_ratio(w->contact_params(site.x_m, site.y_m), deg * kDeg);
    std::printf("wedge %4.1f deg: unaligned k ratio %.5f (predicted %.5f, cos^2 + rho sin^2 "
                "%.5f), aligned %.5f\n",
                deg, k_vertical / k_flat, predicted,
                std::pow(std::cos(deg * kDeg), 2) + kRho * std::pow(std::sin(deg * kDeg), 2),
                k_aligned / k_flat);
    EXPECT_NEAR(k_vertical / k_flat / predicted, 1.0, 3e-3) << deg;
    EXPECT_NEAR(k_aligned / k_flat, 1.0, 3e-3) << deg;
  }
}

}  // namespace
}  // namespace palp::plant
