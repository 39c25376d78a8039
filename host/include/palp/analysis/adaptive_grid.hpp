// SPDX-License-Identifier: Apache-2.0
// The adaptive grid's planner (issue 24, `palpctl map --adaptive`): which point of a plan's
// rows x columns lattice to measure next, from the points measured so far. Pure code: no I/O,
// no device, no state: the next point is a function of the options and of the set of points
// measured (with their stiffness), so a map that stopped resumes with the same decisions by
// asking again with what its map.json holds.
//
// 1. A coarse space-filling design first: a rank-1 lattice of N0 points (default max(rows,
//    columns)), point k at row floor(k rows / N0), column floor(((g k) mod N0) columns / N0),
//    with g coprime to N0 chosen to maximise the smallest distance between the design's points
//    (ties: the smallest g). Every row and every column is sampled (rows and columns <= N0, and
//    g k mod N0 runs through 0..N0-1): no line-periodic pattern aliases away. A stride-s subgrid
//    does alias: on the pad, whose soft columns 2, 5, 8 have period 3, columns 1, 3, 5, 7, 9 see
//    only column 5 and, as 1-3 and 7-9 look alike, refinement would never find 2 and 8.
// 2. Then refinement: an unmeasured point is flagged when the measured points around it (within
//    the coarse design's covering radius D, in Chebyshev distance: every point of the lattice
//    has a design point within D) differ by more than the threshold: 1 - k_min / k_max >
//    threshold (the contrast of analyze_map's soft lines, map.hpp).
//    Among the flagged points the next is the one farthest from every measured point (squared
//    distance in grid steps: the biggest gaps first), then the one whose row and column hold the
//    fewest measured points (the lines stay evenly sampled), then the one whose neighbours
//    differ most, then the first in row-major order.
// 3. It stops at the point budget (default floor(rows columns / 2), at least N0) or when
//    nothing is flagged (a uniform specimen costs the coarse design only).
// A point measured without a stiffness (a failed touch or analysis) counts against the budget,
// is never measured again, and takes no part in the comparisons.
//
// The line means of an irregular sample (line_means): with rows and columns sampled unevenly, a
// row's plain mean depends on which columns happened to be measured in it (a row measured mostly
// on soft columns looks soft). The two-way additive model k(r, c) = mu + a_r + b_c, fitted by
// least squares to the points with a stiffness (sum a_r = sum b_c = 0), gives each line's mean
// as the model predicts it over the whole grid: mu + a_r, mu + b_c. On a complete grid these
// are exactly the plain means.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace palp::analysis {

struct AdaptiveGridOptions {
  int max_points = 0;      ///< the point budget; 0: floor(rows columns / 2), at least coarse_points
  double threshold = 0.1;  ///< neighbours differing by more than this (1 - k_min / k_max) refine
  int coarse_points = 0;   ///< N0, the coarse design's size; 0: max(rows, columns)

  /// ConfigError naming the member: max_points or coarse_points < 0 or more than the grid,
  /// coarse_points above max_points (both resolved), threshold not in (0, 1).
  void validate(int rows, int columns) const;
  /// The budget and the coarse design's size with the defaults applied.
  int budget(int rows, int columns) const;
  int coarse_size(int rows, int columns) const;
  bool operator==(const AdaptiveGridOptions&) const = default;
};

struct GridCell {
  int row = 0, column = 0;  ///< 1-based
  bool operator==(const GridCell&) const = default;
};

struct MeasuredCell {
  int row = 0, column = 0;      ///< 1-based
  std::optional<double> value;  ///< the stiffness; absent when the point gave none
};

/// The coarse design's points in measurement order (n points, each row and column at least once
/// when n >= max(rows, columns)). ConfigError for rows or columns < 1 or n outside 1..rows columns.
std::vector<GridCell> coarse_design(int rows, int columns, int n);

/// The Chebyshev covering radius of `design` on the lattice: every cell is within it of a point.
int covering_radius(int rows, int columns, const std::vector<GridCell>& design);

struct AdaptiveStep {
  std::optional<GridCell> next;  ///< absent: the map is done
  std::string phase;             ///< "coarse", "refine", or why it is done: "budget", "converged"
  double difference = 0;         ///< refine: 1 - k_min / k_max of the point's neighbours
};

/// The next point to measure after `measured` (any order; ConfigError for a point outside the
/// grid or measured twice, or options that do not validate).
AdaptiveStep next_adaptive_point(int rows, int columns, const AdaptiveGridOptions& options,
                                 const std::vector<MeasuredCell>& measured);

/// Each row's and column's mean (row-major results, 1-based lines at index line - 1) from the
/// additive fit above over the cells with a finite value; NaN for a line without one.
struct LineMeans {
  std::vector<double> row, column;
};
LineMeans line_means(int rows, int columns, const std::vector<MeasuredCell>& measured);

}  // namespace palp::analysis
