// SPDX-License-Identifier: Apache-2.0
// K_f(s): the coil's force constant along the stroke, a piecewise-linear table (see config.hpp
// for the default points and README.md for why it is flat over the working range).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "palp/plant/config.hpp"

namespace palp::plant {

class ForceConstantTable {
 public:
  static constexpr std::size_t kMaxPoints = 16;

  /// Points in strictly increasing stroke order, 2..16 of them, positive K_f; throws
  /// std::invalid_argument otherwise.
  explicit ForceConstantTable(const std::vector<KfPoint>& points);

  /// K_f at stroke coordinate s (linear between points, constant beyond the ends), N/A.
  double at(double stroke_m) const;

  /// dK_f/ds at s (the segment's slope; 0 beyond the ends), N/(A*m).
  double slope(double stroke_m) const;

 private:
  std::size_t segment(double stroke_m) const;

  std::array<KfPoint, kMaxPoints> points_{};
  std::size_t count_ = 0;
};

}  // namespace palp::plant
