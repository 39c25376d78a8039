// SPDX-License-Identifier: Apache-2.0
// The adaptive grid's planner: a rank-1 lattice first, then refinement where neighbours differ.
#include "palp/analysis/adaptive_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include <Eigen/Dense>

#include "palp/error.hpp"

namespace palp::analysis {

namespace {

[[noreturn]] void fail(const std::string& problem) {
  throw ConfigError("adaptive grid: " + problem);
}

int squared_distance(const GridCell& a, const GridCell& b) {
  const int dr = a.row - b.row, dc = a.column - b.column;
  return dr * dr + dc * dc;
}

int chebyshev(const GridCell& a, const GridCell& b) {
  return std::max(std::abs(a.row - b.row), std::abs(a.column - b.column));
}

std::vector<GridCell> lattice(int rows, int columns, int n, int g) {
  std::vector<GridCell> out;
  for (long k = 0; k < n; ++k)
    out.push_back(
        {static_cast<int>(k * rows / n) + 1, static_cast<int>((g * k) % n * columns / n) + 1});
  return out;
}

void check_grid(int rows, int columns) {
  if (rows < 1 || columns < 1)
    fail("a grid of " + std::to_string(rows) + " x " + std::to_string(columns) + " points");
}

}  // namespace

void AdaptiveGridOptions::validate(int rows, int columns) const {
  check_grid(rows, columns);
  const int total = rows * columns;
  if (max_points < 0 || max_points > total)
    fail("max_points " + std::to_string(max_points) + " is not in 0.." + std::to_string(total) +
         " (0: half the grid, at least the coarse design)");
  if (coarse_points < 0 || coarse_points > total)
    fail("coarse_points " + std::to_string(coarse_points) + " is not in 0.." +
         std::to_string(total) + " (0: max(rows, columns))");
  if (!(threshold > 0.0 && threshold < 1.0))
    fail("threshold " + std::to_string(threshold) + " is not in (0, 1) (0.1: 10 %)");
  if (coarse_size(rows, columns) > budget(rows, columns))
    fail("the coarse design's " + std::to_string(coarse_size(rows, columns)) +
         " points exceed the budget of " + std::to_string(budget(rows, columns)) +
         " (raise max_points)");
}

int AdaptiveGridOptions::budget(int rows, int columns) const {
  return max_points > 0 ? max_points : std::max(coarse_size(rows, columns), rows * columns / 2);
}

int AdaptiveGridOptions::coarse_size(int rows, int columns) const {
  return coarse_points > 0 ? coarse_points : std::max(rows, columns);
}

std::vector<GridCell> coarse_design(int rows, int columns, int n) {
  check_grid(rows, columns);
  if (n < 1 || n > rows * columns)
    fail(std::to_string(n) + " coarse points for a " + std::to_string(rows) + " x " +
         std::to_string(columns) + " grid");
  // the generator: coprime to n, the largest smallest distance between the design's points
  // (distinct points first: with n > max(rows, columns) some generators repeat a cell)
  std::vector<GridCell> best;
  long best_key = -1;
  for (int g = 1; g <= std::max(1, n - 1); ++g) {
    if (std::gcd(g, n) != 1 && n > 1) continue;
    const std::vector<GridCell> d = lattice(rows, columns, n, g);
    int closest = rows * rows + columns * columns;
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t j = i + 1; j < d.size(); ++j)
        closest = std::min(closest, squared_distance(d[i], d[j]));
    const long key = closest;  // 0 when a cell repeats
    if (key > best_key) best_key = key, best = d;
  }
  if (best_key == 0) {  // every generator repeats a cell: drop the repeats, keep the order
    std::vector<GridCell> unique;
    for (const GridCell& c : best)
      if (std::find(unique.begin(), unique.end(), c) == unique.end()) unique.push_back(c);
    best = unique;
  }
  return best;
}

int covering_radius(int rows, int columns, const std::vector<GridCell>& design) {
  int radius = 0;
  for (int r = 1; r <= rows; ++r)
    for (int c = 1; c <= columns; ++c) {
      int nearest = std::max(rows, columns);
      for (const GridCell& d : design) nearest = std::min(nearest, chebyshev({r, c}, d));
      radius = std::max(radius, nearest);
    }
  return radius;
}

AdaptiveStep next_adaptive_point(int rows, int columns, const AdaptiveGridOptions& o,
                                 const std::vector<MeasuredCell>& measured) {
  o.validate(rows, columns);
  std::vector<char> done(static_cast<std::size_t>(rows * columns), 0);
  for (const MeasuredCell& m : measured) {
    if (m.row < 1 || m.row > rows || m.column < 1 || m.column > columns)
      fail("measured point (row " + std::to_string(m.row) + ", column " + std::to_string(m.column) +
           ") outside the " + std::to_string(rows) + " x " + std::to_string(columns) + " grid");
    char& d = done[static_cast<std::size_t>((m.row - 1) * columns + m.column - 1)];
    if (d)
      fail("point (row " + std::to_string(m.row) + ", column " + std::to_string(m.column) +
           ") measured twice");
    d = 1;
  }
  auto is_done = [&](const GridCell& c) {
    return done[static_cast<std::size_t>((c.row - 1) * columns + c.column - 1)] != 0;
  };
  AdaptiveStep step;
  if (static_cast<int>(measured.size()) >= o.budget(rows, columns)) {
    step.phase = "budget";
    return step;
  }
  const std::vector<GridCell> design = coarse_design(rows, columns, o.coarse_size(rows, columns));
  for (const GridCell& c : design)
    if (!is_done(c)) {
      step.next = c;
      step.phase = "coarse";
      return step;
    }
  const int radius = std::max(1, covering_radius(rows, columns, design));
  // every unmeasured point: flagged when its measured neighbours differ by more than the threshold
  struct Candidate {
    GridCell cell;
    int gap;
    int crowd;  ///< the points measured in its row and its column
    double difference;
  };
  std::vector<int> in_row(static_cast<std::size_t>(rows), 0),
      in_column(static_cast<std::size_t>(columns), 0);
  for (const MeasuredCell& m : measured)
    ++in_row[static_cast<std::size_t>(m.row - 1)],
        ++in_column[static_cast<std::size_t>(m.column - 1)];
  std::optional<Candidate> best;
  for (int r = 1; r <= rows; ++r)
    for (int c = 1; c <= columns; ++c) {
      const GridCell cell{r, c};
      if (is_done(cell)) continue;
      double lo = INFINITY, hi = -INFINITY;
      int gap = rows * rows + columns * columns;
      for (const MeasuredCell& m : measured) {
        const GridCell at{m.row, m.column};
        gap = std::min(gap, squared_distance(cell, at));
        if (!m.value || !std::isfinite(*m.value) || chebyshev(cell, at) > radius) continue;
        lo = std::min(lo, *m.value);
        hi = std::max(hi, *m.value);
      }
      if (!(hi > 0.0) || !(lo <= hi)) continue;
      const double difference = 1.0 - lo / hi;
      if (!(difference > o.threshold)) continue;
      const int crowd =
          in_row[static_cast<std::size_t>(r - 1)] + in_column[static_cast<std::size_t>(c - 1)];
      // row-major scan: a later point wins only by a larger gap, or the same gap and fewer measured
      // points around it, or those and a larger difference
      if (!best || gap > best->gap || (gap == best->gap && crowd < best->crowd) ||
          (gap == best->gap && crowd == best->crowd && difference > best->difference))
        best = Candidate{cell, gap, crowd, difference};
    }
  if (!best) {
    step.phase = "converged";
    return step;
  }
  step.next = best->cell;
  step.phase = "refine";
  step.difference = best->difference;
  return step;
}

LineMeans line_means(int rows, int columns, const std::vector<MeasuredCell>& measured) {
  check_grid(rows, columns);
  std::vector<const MeasuredCell*> used;
  std::vector<char> row_has(static_cast<std::size_t>(rows), 0),
      column_has(static_cast<std::size_t>(columns), 0);
  for (const MeasuredCell& m : measured) {
    if (m.row < 1 || m.row > rows || m.column < 1 || m.column > columns || !m.value ||
        !std::isfinite(*m.value))
      continue;
    used.push_back(&m);
    row_has[static_cast<std::size_t>(m.row - 1)] =
        column_has[static_cast<std::size_t>(m.column - 1)] = 1;
  }
  LineMeans out;
  out.row.assign(static_cast<std::size_t>(rows), NAN);
  out.column.assign(static_cast<std::size_t>(columns), NAN);
  if (used.empty()) return out;
  // unknowns: mu, a_1..a_rows, b_1..b_columns; a line without a value keeps its effect at zero
  // (minimum norm) and gets NaN; the two sums fix the gauge and cost nothing in the fit
  const Eigen::Index n = 1 + rows + columns, eq = static_cast<Eigen::Index>(used.size()) + 2;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(eq, n);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(eq);
  for (std::size_t i = 0; i < used.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    A(k, 0) = 1;
    A(k, used[i]->row) = 1;
    A(k, rows + used[i]->column) = 1;
    y(k) = *used[i]->value;
  }
  for (int r = 1; r <= rows; ++r) A(eq - 2, r) = row_has[static_cast<std::size_t>(r - 1)] ? 1 : 0;
  for (int c = 1; c <= columns; ++c)
    A(eq - 1, rows + c) = column_has[static_cast<std::size_t>(c - 1)] ? 1 : 0;
  const Eigen::VectorXd x = A.completeOrthogonalDecomposition().solve(y);
  for (int r = 1; r <= rows; ++r)
    if (row_has[static_cast<std::size_t>(r - 1)])
      out.row[static_cast<std::size_t>(r - 1)] = x(0) + x(r);
  for (int c = 1; c <= columns; ++c)
    if (column_has[static_cast<std::size_t>(c - 1)])
      out.column[static_cast<std::size_t>(c - 1)] = x(0) + x(rows + c);
  return out;
}

}  // namespace palp::analysis
