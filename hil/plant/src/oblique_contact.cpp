// SPDX-License-Identifier: Apache-2.0
// A sphere pressed along an axis tilted from the surface normal (README.md "Oblique contact"):
// Mindlin's tangential stiffness and Johnson's oblique loading at a constant ratio.
#include <algorithm>
#include <cmath>

#include "palp/plant/contact.hpp"

namespace palp::plant {

double mindlin_stiffness_ratio(double poisson_ratio) {
  // k_t / k_n = 8 G a / (2 - nu) over 2 E a / (1 - nu^2), with E = 2 G (1 + nu)
  return 2.0 * (1.0 - poisson_ratio) / (2.0 - poisson_ratio);
}

ObliqueSplit oblique_split(double cos_theta, double friction_coefficient) {
  ObliqueSplit s;
  if (cos_theta >= 1.0) return s;  // the normal law, exactly
  s.cos_theta = cos_theta;
  s.sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double stick = mindlin_stiffness_ratio(kPoissonRatio) * s.sin_theta / cos_theta;
  s.sliding = stick > friction_coefficient;
  s.tangential_per_normal = s.sliding ? friction_coefficient : stick;
  s.axial_per_normal = cos_theta + s.tangential_per_normal * s.sin_theta;
  s.lateral_per_normal = s.sin_theta - s.tangential_per_normal * cos_theta;
  return s;
}

ElasticPoint oblique_elastic_contact(const ContactParams& params, double radius_m,
                                     double axial_depth_m, double cos_theta) {
  if (cos_theta >= 1.0) return elastic_contact(params, radius_m, axial_depth_m);
  const ObliqueSplit s = oblique_split(cos_theta, params.friction_coefficient);
  const ElasticPoint n = elastic_contact(params, radius_m, axial_depth_m * s.cos_theta);
  return {n.force_N * s.axial_per_normal, n.stiffness_N_per_m * s.cos_theta * s.axial_per_normal};
}

}  // namespace palp::plant
