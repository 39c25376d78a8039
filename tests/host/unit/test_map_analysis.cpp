// SPDX-License-Identifier: Apache-2.0
// analyze_map on a map of known stiffness: soft lines against the median line, absent points.
#include <gtest/gtest.h>

#include "palp/map.hpp"

namespace {

palp::StiffnessMap grid(int rows, int cols, const std::function<std::optional<double>(int, int)>& k) {
  palp::StiffnessMap m;
  m.rows = rows;
  m.columns = cols;
  for (int r = 1; r <= rows; ++r)
    for (int c = 1; c <= cols; ++c) {
      palp::MapPoint p;
      p.row = r;
      p.column = c;
      p.k_fd_N_per_m = k(r, c);
      m.points.push_back(p);
    }
  return m;
}

TEST(MapAnalysis, ColumnsOverChannelsAreSoftAndTheirNeighboursAreNotCalledStiff) {
  // 3 N/mm everywhere, 2 N/mm on columns 2, 5, 8
  const auto m = grid(9, 9, [](int, int c) { return (c == 2 || c == 5 || c == 8) ? 2000.0 : 3000.0; });
  const palp::MapAnalysis a = palp::analyze_map(m, 0.1);
  EXPECT_EQ(a.soft_columns, (std::vector<int>{2, 5, 8}));
  EXPECT_TRUE(a.stiff_columns.empty());
  EXPECT_TRUE(a.soft_rows.empty());
  EXPECT_TRUE(a.stiff_rows.empty());
  EXPECT_DOUBLE_EQ(a.column_mean_N_per_m[1], 2000.0);
  EXPECT_DOUBLE_EQ(a.row_mean_N_per_m[0], (6 * 3000.0 + 3 * 2000.0) / 9);
  EXPECT_DOUBLE_EQ(a.median_N_per_m, 3000.0);
}

TEST(MapAnalysis, AStiffRowStandsOutAndAnAbsentPointIsLeftOutOfTheMeans) {
  const auto m = grid(5, 4, [](int r, int c) -> std::optional<double> {
    if (r == 1 && c == 1) return std::nullopt;  // failed point
    return r == 3 ? 1500.0 : 1000.0;
  });
  const palp::MapAnalysis a = palp::analyze_map(m, 0.2);
  EXPECT_EQ(a.stiff_rows, (std::vector<int>{3}));
  EXPECT_TRUE(a.soft_rows.empty());
  EXPECT_FALSE(a.k_N_per_m[0].has_value());
  EXPECT_DOUBLE_EQ(a.row_mean_N_per_m[0], 1000.0);  // three points, not four
  EXPECT_DOUBLE_EQ(a.column_mean_N_per_m[0], (3 * 1000.0 + 1500.0) / 4);
}

}  // namespace
