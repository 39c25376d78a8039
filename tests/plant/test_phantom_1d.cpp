// SPDX-License-Identifier: Apache-2.0
// The 1D objects along their ten positions (paper §IV-A, Fig. 4c), from their contact laws:
// insert > solid > hollow at positions 1-4, the three agree at 6-10, position 8 is the stiffest
// of 6-10, and over the hollow's void the stiffness hardly changes with depth.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "palp/plant/phantom.hpp"
#include "plant_test_util.hpp"

namespace palp::plant {
namespace {

using test::kR;

double tangent(const Phantom& ph, int position, double depth_m) {
  const ProbeSite s = ph.position(position);
  return elastic_contact(ph.contact_params(s.x_m, s.y_m), kR, depth_m).stiffness_N_per_m;
}

class Line1D : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    hollow_ = load_shipped_phantom("hollow_1d");
    solid_ = load_shipped_phantom("solid_1d");
    insert_ = load_shipped_phantom("insert_1d");
  }
  static inline std::shared_ptr<const Phantom> hollow_, solid_, insert_;
};

TEST_F(Line1D, PositionsAre9mmApartOnAFlatTop) {
  for (int k = 1; k <= 10; ++k) {
    EXPECT_NEAR(solid_->position(k).x_m, 0.009 * k, 1e-12);
    EXPECT_EQ(solid_->surface_z_m(solid_->position(k).x_m, 0.0), 0.0);
  }
  EXPECT_EQ(solid_->surface_z_m(0.12, 0.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(solid_->surface_z_m(0.05, 0.02), std::numeric_limits<double>::infinity());
}

TEST_F(Line1D, InsertStifferThanSolidStifferThanHollowAtPositions1To4) {
  for (int k = 1; k <= 4; ++k) {
    for (double d : {1e-3, 2e-3, 3e-3, 4e-3}) {
      EXPECT_GT(tangent(*insert_, k, d), 1.05 * tangent(*solid_, k, d)) << k << " " << d;
      EXPECT_GT(tangent(*solid_, k, d), 1.05 * tangent(*hollow_, k, d)) << k << " " << d;
    }
  }
}

TEST_F(Line1D, ObjectsConvergeAtPositions6To10) {
  for (int k = 6; k <= 10; ++k) {
    for (double d : {1e-3, 2e-3, 3e-3, 4e-3}) {
      const double s = tangent(*solid_, k, d);
      EXPECT_NEAR(tangent(*insert_, k, d), s, 1e-9 * s);
      EXPECT_NEAR(tangent(*hollow_, k, d), s, 1e-9 * s);
    }
  }
}

TEST_F(Line1D, Position8IsTheStiffestOf6To10) {
  for (const auto* ph : {&hollow_, &solid_, &insert_}) {
    for (double d : {1e-3, 2e-3, 3e-3, 4e-3}) {
      for (int k : {6, 7, 9, 10}) EXPECT_GT(tangent(**ph, 8, d), tangent(**ph, k, d));
    }
  }
}

TEST_F(Line1D, HollowVoidPositionsStayNearlyUniformWithDepthUnlikeTheSolid) {
  for (int k = 1; k <= 3; ++k) {
    EXPECT_LT(tangent(*hollow_, k, 4e-3) / tangent(*hollow_, k, 1e-3), 1.15) << k;
    EXPECT_GT(tangent(*solid_, k, 4e-3) / tangent(*solid_, k, 1e-3), 1.6) << k;
  }
}

TEST_F(Line1D, ParticipatingMassGrowsFromInsertToHollowAtPosition3) {
  const ProbeSite s = solid_->position(3);
  const double mi = insert_->contact_params(s.x_m, 0).participating_mass_kg;
  const double ms = solid_->contact_params(s.x_m, 0).participating_mass_kg;
  const double mh = hollow_->contact_params(s.x_m, 0).participating_mass_kg;
  EXPECT_LT(mi, ms);
  EXPECT_LT(ms, mh);
}

}  // namespace
}  // namespace palp::plant
