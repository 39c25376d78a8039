// SPDX-License-Identifier: Apache-2.0
// The Vega helpers (host/src/report/vega_build.hpp): rows, extents, heat maps.
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "report/vega_build.hpp"

namespace vega = palp::report::vega;

TEST(VegaBuild, RowsZipColumnsAndWriteNonFiniteAsNull) {
  const auto r = vega::rows({{"x_mm", {1.0, 2.0}}, {"F_N", {0.5, std::nan("")}}});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0]["x_mm"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(r[0]["F_N"].get<double>(), 0.5);
  EXPECT_TRUE(r[1]["F_N"].is_null());
}

TEST(VegaBuild, RowsRejectColumnsOfDifferentLengths) {
  EXPECT_THROW(vega::rows({{"a", {1.0}}, {"b", {1.0, 2.0}}}), std::invalid_argument);
}

TEST(VegaBuild, ExtentIgnoresNonFiniteAndPadsTheSpan) {
  vega::Extent e;
  e.add({2.0, std::numeric_limits<double>::infinity(), 4.0, std::nan("")});
  EXPECT_EQ(e.domain(0.5), vega::json::array({1.0, 5.0}));
  vega::Extent one;
  one.add(3.0);
  EXPECT_EQ(one.domain(), vega::json::array({2.0, 4.0}));
  EXPECT_EQ(vega::Extent{}.domain(), vega::json::array({0.0, 1.0}));
}

TEST(VegaBuild, LogDomainUsesThePositiveValues) {
  vega::Extent e;
  e.add({1e-4, 1e-2});
  EXPECT_EQ(e.log_domain(), vega::json::array({1e-4, 1e-2}));
}

TEST(VegaBuild, HeatMapHoldsEveryCellWithItsGridPositionAndAColourBar) {
  std::vector<vega::HeatCell> cells;
  for (int r = 1; r <= 2; ++r)
    for (int c = 1; c <= 3; ++c) cells.push_back({r, c, 10.0 * r + c, {{"id", r * 10 + c}}});
  cells.back().value = std::nan("");
  vega::HeatMapStyle style;
  style.value_title = "h (mm)";
  const auto s = vega::heat_map(2, 3, cells, style);
  EXPECT_EQ(s["width"], 3 * style.cell_px);
  EXPECT_EQ(s["height"], 2 * style.cell_px);
  const auto& values = s["data"][0]["values"];
  ASSERT_EQ(values.size(), 6u);
  EXPECT_EQ(values[4]["row"], 2);
  EXPECT_EQ(values[4]["column"], 2);
  EXPECT_DOUBLE_EQ(values[4]["value"].get<double>(), 22.0);
  EXPECT_EQ(values[4]["id"], 22);
  EXPECT_TRUE(values[5]["value"].is_null());
  EXPECT_EQ(s["scales"][2]["domain"], vega::json::array({11.0, 22.0}));  // the missing one left out
  EXPECT_EQ(s["legends"][0]["type"], "gradient");
  EXPECT_EQ(s["legends"][0]["title"], "h (mm)");
}

TEST(VegaBuild, HeatMapRejectsACellOutsideTheGrid) {
  EXPECT_THROW(vega::heat_map(2, 2, {{3, 1, 1.0, {}}}, {}), std::invalid_argument);
  EXPECT_THROW(vega::heat_map(0, 2, {}, {}), std::invalid_argument);
}

TEST(VegaBuild, HeatMapCellsLinkWhereTheyHaveAnHrefAndOutlinesMarkWholeColumnsAndRows) {
  std::vector<vega::HeatCell> cells;
  for (int r = 1; r <= 3; ++r)
    for (int c = 1; c <= 3; ++c) cells.push_back({r, c, 1.0 * c, {{"href", "#p" + std::to_string(r * 10 + c)}}});
  vega::HeatMapStyle style;
  style.value_title = "k_fd (N/mm)";
  auto s = vega::heat_map(3, 3, cells, style);
  EXPECT_EQ(s["marks"][0]["encode"]["enter"]["href"], (vega::json{{"field", "href"}}));
  EXPECT_EQ(s["data"][0]["values"][4]["href"], "#p22");
  vega::outline_columns(s, {2}, "#D55E00", "soft", "soft_columns");
  vega::outline_rows(s, {1, 3}, "#0072B2", "stiff", "stiff_rows");
  const auto data = [&](const std::string& name) {
    for (const auto& d : s["data"])
      if (d["name"] == name) return d["values"];
    return vega::json();
  };
  EXPECT_EQ(data("soft_columns_data"), (vega::json::array({{{"index", 2}}})));
  EXPECT_EQ(data("stiff_rows_data"), (vega::json::array({{{"index", 1}}, {{"index", 3}}})));
  EXPECT_GT(s["legends"][0]["offset"].get<int>(), 18);  // the colour bar clear of "stiff"
  // without links the cells carry none
  EXPECT_FALSE(vega::heat_map(1, 1, {{1, 1, 1.0, {}}}, style)["marks"][0]["encode"]["enter"].contains("href"));
}
