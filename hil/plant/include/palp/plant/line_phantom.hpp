// SPDX-License-Identifier: Apache-2.0
// The paper's 1D test objects (§IV): a bar with ten probing positions along x, each with its own
// contact law (the file lists one value per position); between positions the law is
// interpolated linearly in x (the layer thickness in 1/h, so "0 = half-space" blends smoothly).
#pragma once

#include <vector>

#include "palp/plant/phantom.hpp"

namespace palp::plant {

struct LinePhantomSpec : MaterialSpec {
  double length_m = 0.0;            // footprint x in [0, length]
  double width_m = 0.0;             // footprint y in [-width/2, width/2]
  double first_position_x_m = 0.0;  // x of position 1
  double position_pitch_m = 0.0;    // 9 mm in the paper
  double surface_z_m = 0.0;         // flat top
  // One value per position (position k at index k - 1):
  std::vector<double> e_star_Pa;
  std::vector<double> layer_thickness_m;  // 0 = half-space
  std::vector<double> structural_compliance_m_per_N;
  std::vector<double> participating_mass_kg;
  std::vector<double> retardation_time_s;
};

class LinePhantom final : public Phantom {
 public:
  /// Throws PhantomError("name: ...") if the tables differ in length or are empty.
  explicit LinePhantom(LinePhantomSpec spec);

  double surface_z_m(double x_m, double y_m) const override;
  ContactParams contact_params(double x_m, double y_m) const override;
  std::vector<ProbeSite> sites() const override;

  const LinePhantomSpec& spec() const { return spec_; }

 private:
  LinePhantomSpec spec_;
};

}  // namespace palp::plant
