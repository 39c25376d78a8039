// SPDX-License-Identifier: Apache-2.0
// The K_f(s) table: default points and piecewise-linear lookup.
#include "palp/plant/force_constant.hpp"

#include <stdexcept>

namespace palp::plant {

std::vector<KfPoint> default_kf_table() {
  return {
      {0.000, 3.30},    // assumed: rear end of the stroke (the coil parks here at 0 A)
      {0.017, 3.84},    // paper §II-A: 3.84 N/A near mid-stroke (34 mm stroke, mid at 17 mm)
      {0.0235, 2.918},  // paper §II-A: 2.918 N/A at 24 mm travel (flat from 23.5 mm on, so the
                        // working range starts 0.5 mm inside the flat part)
      {0.034, 2.918},   // flat to the front stop: the working range s_f - 1 mm .. s_f + 6 mm
                        // (24..31 mm) and beyond is kept free of a hidden spring i dK_f/ds
  };
}

ForceConstantTable::ForceConstantTable(const std::vector<KfPoint>& points) {
  if (points.size() < 2 || points.size() > kMaxPoints) {
    throw std::invalid_argument("force-constant table needs 2..16 points");
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!(points[k].kf_N_per_A > 0.0)) {
      throw std::invalid_argument("force-constant table: K_f must be positive");
    }
    if (k > 0 && !(points[k].stroke_m > points[k - 1].stroke_m)) {
      throw std::invalid_argument("force-constant table: stroke positions must increase");
    }
    points_[k] = points[k];
  }
  count_ = points.size();
}

std::size_t ForceConstantTable::segment(double stroke_m) const {
  std::size_t k = 0;
  while (k + 2 < count_ && stroke_m > points_[k + 1].stroke_m) ++k;
  return k;
}

double ForceConstantTable::at(double stroke_m) const {
  if (stroke_m <= points_[0].stroke_m) return points_[0].kf_N_per_A;
  if (stroke_m >= points_[count_ - 1].stroke_m) return points_[count_ - 1].kf_N_per_A;
  const std::size_t k = segment(stroke_m);
  const KfPoint& a = points_[k];
  const KfPoint& b = points_[k + 1];
  const double t = (stroke_m - a.stroke_m) / (b.stroke_m - a.stroke_m);
  return a.kf_N_per_A + t * (b.kf_N_per_A - a.kf_N_per_A);
}

double ForceConstantTable::slope(double stroke_m) const {
  if (stroke_m < points_[0].stroke_m || stroke_m > points_[count_ - 1].stroke_m) return 0.0;
  const std::size_t k = segment(stroke_m);
  const KfPoint& a = points_[k];
  const KfPoint& b = points_[k + 1];
  return (b.kf_N_per_A - a.kf_N_per_A) / (b.stroke_m - a.stroke_m);
}

}  // namespace palp::plant
