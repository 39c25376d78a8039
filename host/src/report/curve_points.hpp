// SPDX-License-Identifier: Apache-2.0
// The points a report's force–depth and pressure–force figures draw from a recording: one per
// staircase plateau (the mean of its samples), so that a 1 kHz ramp of thousands of samples
// becomes a few hundred points per repetition and the embedded data stay small.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "palp/analysis/indentation.hpp"

namespace palp::report {

/// Consecutive samples of one repetition on one branch at one commanded current (a plateau of
/// the staircase); without the commanded-current column, runs of consecutive samples, as many
/// as keep a repetition under `max_per_rep` groups. In time order; every sample in one group.
struct PointGroup {
  int rep = 0;           ///< the curve's repetition number
  bool loading = false;  ///< on the loading branch (analysis::loading_branch)
  std::vector<Eigen::Index> samples;
};
std::vector<PointGroup> plateau_groups(const analysis::Curve& c, int max_per_rep = 600);

/// The plateaus of one commanded current on one branch, one from each repetition: a mean ± s.d.
/// over repetitions there (the paper's Fig. 5(c)). Loading levels upwards, then unloading
/// downwards. Empty without the commanded-current column.
struct Level {
  bool loading = false;
  double i_cmd_A = 0;
  std::vector<std::size_t> groups;  ///< indices into plateau_groups' result
};
std::vector<Level> levels_over_repetitions(const analysis::Curve& c,
                                           const std::vector<PointGroup>& groups);

/// The mean of v over a group's samples.
double group_mean(const Eigen::VectorXd& v, const PointGroup& g);

/// The curve's repetition numbers in the order they first appear.
std::vector<int> repetitions_of(const analysis::Curve& c);

}  // namespace palp::report
