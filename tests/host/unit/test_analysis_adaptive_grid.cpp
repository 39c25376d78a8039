// SPDX-License-Identifier: Apache-2.0
// The adaptive grid's planner on known stiffness fields: a coarse design that sees every row and
// column, refinement that finds the pad's soft columns within half the grid, a uniform field
// that stops after the coarse design, and decisions that depend only on what was measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "palp/analysis/adaptive_grid.hpp"
#include "palp/error.hpp"
#include "palp/map.hpp"

namespace {

using palp::analysis::AdaptiveGridOptions;
using palp::analysis::GridCell;
using palp::analysis::MeasuredCell;

using Field = std::function<std::optional<double>(int, int)>;

/// The pad's pattern (k_fd N/m): columns 2, 5, 8 25 % softer, rows 2, 5, 8 (deep channels) 3 %,
/// and a deterministic +-1 % ripple standing in for noise.
std::optional<double> pad(int r, int c) {
  const double col = (c == 2 || c == 5 || c == 8) ? 0.75 : 1.0,
               row = (r == 2 || r == 5 || r == 8) ? 0.97 : 1.0;
  return 3000.0 * col * row * (1.0 + 0.01 * std::sin(7.0 * r + 3.0 * c));
}

/// Runs the planner to its end, measuring `field`; the points in measurement order.
std::vector<MeasuredCell> run(int rows, int columns, const AdaptiveGridOptions& o,
                              const Field& field, std::string* ended = nullptr) {
  std::vector<MeasuredCell> measured;
  for (;;) {
    const palp::analysis::AdaptiveStep s =
        palp::analysis::next_adaptive_point(rows, columns, o, measured);
    if (!s.next) {
      if (ended) *ended = s.phase;
      return measured;
    }
    measured.push_back({s.next->row, s.next->column, field(s.next->row, s.next->column)});
  }
}

palp::StiffnessMap as_map(int rows, int columns, const std::vector<MeasuredCell>& measured) {
  palp::StiffnessMap m;
  m.rows = rows;
  m.columns = columns;
  m.adaptive = AdaptiveGridOptions{};  // analyze_map's line means from the additive fit
  for (const MeasuredCell& c : measured) {
    palp::MapPoint p;
    p.row = c.row;
    p.column = c.column;
    p.k_fd_N_per_m = c.value;
    m.points.push_back(p);
  }
  return m;
}

TEST(AdaptiveGrid, TheCoarseDesignSamplesEveryRowAndEveryColumnOnce) {
  for (const auto& [rows, columns] :
       {std::pair{9, 9}, {3, 9}, {9, 3}, {5, 4}, {1, 7}, {2, 2}, {6, 10}}) {
    const int n = std::max(rows, columns);
    const auto d = palp::analysis::coarse_design(rows, columns, n);
    ASSERT_EQ(d.size(), static_cast<std::size_t>(n)) << rows << " x " << columns;
    std::set<int> r, c;
    std::set<std::pair<int, int>> cells;
    for (const GridCell& g : d)
      r.insert(g.row), c.insert(g.column), cells.insert({g.row, g.column});
    EXPECT_EQ(r.size(), static_cast<std::size_t>(rows)) << rows << " x " << columns;
    EXPECT_EQ(c.size(), static_cast<std::size_t>(columns)) << rows << " x " << columns;
    EXPECT_EQ(cells.size(), d.size()) << "a cell twice, " << rows << " x " << columns;
  }
  // 9 x 9: a permutation (one point per row and column), g = 2; every cell within 3 of a point
  const auto d = palp::analysis::coarse_design(9, 9, 9);
  EXPECT_EQ(d[1], (GridCell{2, 3}));
  EXPECT_EQ(d[5], (GridCell{6, 2}));
  EXPECT_EQ(palp::analysis::covering_radius(9, 9, d), 3);
}

TEST(AdaptiveGrid, AStrideTwoGridWouldMissColumnsTwoAndEightButTheDesignSeesThem) {
  // the stride-2 subgrid's columns 1, 3, 5, 7, 9: only column 5 of the soft ones
  std::set<int> stride2;
  for (int c = 1; c <= 9; c += 2) stride2.insert(c);
  EXPECT_EQ(stride2.count(2) + stride2.count(8), 0u);
  // the design's first nine points already give columns 2, 5 and 8 as analyze_map's soft ones
  AdaptiveGridOptions o;
  o.max_points = 9;
  std::string ended;
  const auto coarse = run(9, 9, o, pad, &ended);
  EXPECT_EQ(ended, "budget");
  EXPECT_EQ(palp::analyze_map(as_map(9, 9, coarse), 0.1).soft_columns, (std::vector<int>{2, 5, 8}));
}

TEST(AdaptiveGrid, OnThePadPatternItFindsColumns258SoftWithinFortyPointsAtTheFullMapsContrast) {
  AdaptiveGridOptions o;  // 40 of 81, threshold 10 %
  std::string ended;
  const auto m = run(9, 9, o, pad, &ended);
  EXPECT_EQ(ended, "budget");
  EXPECT_EQ(m.size(), 40u);
  std::vector<MeasuredCell> full;
  for (int r = 1; r <= 9; ++r)
    for (int c = 1; c <= 9; ++c) full.push_back({r, c, pad(r, c)});
  const palp::MapAnalysis a = palp::analyze_map(as_map(9, 9, m), 0.1),
                          f = palp::analyze_map(as_map(9, 9, full), 0.1);
  EXPECT_EQ(a.soft_columns, f.soft_columns);
  EXPECT_EQ(a.soft_columns, (std::vector<int>{2, 5, 8}));
  EXPECT_TRUE(a.soft_rows.empty() && a.stiff_rows.empty() && a.stiff_columns.empty());
  // every column measured at least three times
  for (int c = 1; c <= 9; ++c)
    EXPECT_GE(
        std::count_if(m.begin(), m.end(), [c](const MeasuredCell& p) { return p.column == c; }), 3)
        << c;
}

TEST(AdaptiveGrid, AUniformFieldStopsAfterTheCoarseDesignAndAStepRefinesAlongItsEdge) {
  AdaptiveGridOptions o;
  std::string ended;
  const auto uniform = run(
      9, 9, o, [](int r, int c) { return 3000.0 * (1.0 + 0.01 * std::sin(r + 2.0 * c)); }, &ended);
  EXPECT_EQ(ended, "converged");
  EXPECT_EQ(uniform.size(), 9u);
  // a step between columns 4 and 5 (half as stiff right of it): every refined point lies within the
  // covering radius (3) of points on both sides, i.e. in columns 2..7, and those fill up first
  o.max_points = 60;
  const auto step = run(
      9, 9, o, [](int, int c) { return c <= 4 ? 3000.0 : 1500.0; }, &ended);
  EXPECT_EQ(ended, "converged");
  for (std::size_t k = 9; k < step.size(); ++k)
    EXPECT_TRUE(step[k].column >= 2 && step[k].column <= 7)
        << "point " << k << " at column " << step[k].column;
  EXPECT_EQ(step.size(), 9u + 6 * 9 - 6);  // the coarse design's 9, then all of columns 2..7
}

TEST(AdaptiveGrid, TheNextPointDependsOnlyOnTheSetMeasuredSoAResumedMapDecidesTheSame) {
  AdaptiveGridOptions o;
  const auto m = run(9, 9, o, pad);
  // any prefix, in reverse order, asks for the point that followed it
  for (std::size_t k = 0; k < m.size(); ++k) {
    std::vector<MeasuredCell> prefix(m.begin(), m.begin() + static_cast<long>(k));
    std::reverse(prefix.begin(), prefix.end());
    const auto s = palp::analysis::next_adaptive_point(9, 9, o, prefix);
    ASSERT_TRUE(s.next.has_value()) << k;
    EXPECT_EQ(*s.next, (GridCell{m[k].row, m[k].column})) << "after " << k << " points";
  }
}

TEST(AdaptiveGrid, APointWithoutStiffnessCountsAgainstTheBudgetAndIsNotMeasuredAgain) {
  AdaptiveGridOptions o;
  o.max_points = 20;
  const auto m = run(9, 9, o, [](int r, int c) -> std::optional<double> {
    if (r == 2 && c == 3) return std::nullopt;  // the design's second point fails
    return pad(r, c);
  });
  EXPECT_EQ(m.size(), 20u);
  EXPECT_EQ(std::count_if(m.begin(), m.end(),
                          [](const MeasuredCell& p) { return p.row == 2 && p.column == 3; }),
            1);
}

TEST(AdaptiveGrid, LineMeansOfAnUnevenSampleAreTheAdditiveModelsNotThePlainMeans) {
  // k = 1000 + 100 r + 10 c (exactly additive): row 1 measured only at column 9, row 2 at 1..9
  std::vector<MeasuredCell> m{{1, 9, 1000.0 + 100 + 90}};
  for (int c = 1; c <= 9; ++c) m.push_back({2, c, 1000.0 + 200 + 10.0 * c});
  const auto lm = palp::analysis::line_means(3, 9, m);
  EXPECT_NEAR(lm.row[0], 1000.0 + 100 + 50, 1e-9);  // its plain mean would be 1190
  EXPECT_NEAR(lm.row[1], 1000.0 + 200 + 50, 1e-9);
  EXPECT_TRUE(std::isnan(lm.row[2]));
  EXPECT_NEAR(lm.column[8], 1000.0 + 150 + 90, 1e-9);  // over rows 1 and 2 (the rows with a value)
  // a complete grid: exactly the plain means
  std::vector<MeasuredCell> full;
  for (int r = 1; r <= 4; ++r)
    for (int c = 1; c <= 3; ++c) full.push_back({r, c, pad(r, c)});
  const auto f = palp::analysis::line_means(4, 3, full);
  for (int c = 1; c <= 3; ++c) {
    double s = 0;
    for (int r = 1; r <= 4; ++r) s += *pad(r, c);
    EXPECT_NEAR(f.column[static_cast<std::size_t>(c - 1)], s / 4, 1e-9 * s);
  }
}

TEST(AdaptiveGrid, BadOptionsAndPointsAreRefusedNamingTheProblem) {
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const palp::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  AdaptiveGridOptions o;
  o.threshold = 0;
  EXPECT_EQ(message([&] { o.validate(9, 9); }),
            "adaptive grid: threshold 0.000000 is not in (0, 1) (0.1: 10 %)");
  o = {};
  o.max_points = 5;
  EXPECT_EQ(
      message([&] { o.validate(9, 9); }),
      "adaptive grid: the coarse design's 9 points exceed the budget of 5 (raise max_points)");
  o.max_points = 82;
  EXPECT_EQ(message([&] { o.validate(9, 9); }),
            "adaptive grid: max_points 82 is not in 0..81 (0: half the grid, at least the coarse "
            "design)");
  o = {};
  EXPECT_EQ(message([&] {
              palp::analysis::next_adaptive_point(9, 9, o, {{1, 1, 1.0}, {1, 1, 2.0}});
            }),
            "adaptive grid: point (row 1, column 1) measured twice");
  EXPECT_EQ(message([&] {
              palp::analysis::next_adaptive_point(9, 9, o, {{10, 1, 1.0}});
            }),
            "adaptive grid: measured point (row 10, column 1) outside the 9 x 9 grid");
}

}  // namespace
