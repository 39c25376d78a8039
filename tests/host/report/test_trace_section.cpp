// SPDX-License-Identifier: Apache-2.0
// The trace section's maps (host/src/report/trace_section.cpp) from a known tilted plane:
// z = 10 + 0.5 (column − 1) mm, every normal tilted 2.862° towards −x, one failed point.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "palp/error.hpp"
#include "report/sections.hpp"
#include "report_plots_synth.hpp"

namespace {

using nlohmann::json;
using palp_test::report::data_values;
namespace rt = palp_test::report;

const json& cell(const json& cells, int row, int column) {
  for (const auto& c : cells)
    if (c["row"] == row && c["column"] == column) return c;
  throw std::out_of_range("no cell");
}

TEST(TraceSection, HeightsMapHoldsEveryGridPointsKnownZAndTheFailedOnesReason) {
  const auto s = palp::report::trace_section(rt::known_trace());
  ASSERT_EQ(s.figures.size(), 2u);
  const json& spec = s.figures[0].spec;
  EXPECT_EQ(s.figures[0].id, "trace-heights");
  EXPECT_EQ(spec["legends"][0]["title"], "z (mm)");
  EXPECT_EQ(spec["legends"][0]["type"], "gradient");
  const json& cells = data_values(spec, "cells");
  ASSERT_EQ(cells.size(), 20u);
  for (int r = 1; r <= 4; ++r)
    for (int c = 1; c <= 5; ++c) {
      const json& x = cell(cells, r, c);
      if (r == 2 && c == 3) {
        EXPECT_TRUE(x["value"].is_null());
        EXPECT_EQ(x["status"], "no contact within 15.000 mm of travel");
      } else {
        EXPECT_NEAR(x["value"].get<double>(), 10.0 + 0.5 * (c - 1), 1e-12);
      }
    }
  EXPECT_EQ(spec["scales"][2]["domain"], json::array({10.0, 12.0}));  // the colour bar's span
  EXPECT_THAT(s.text, testing::HasSubstr("19 of 20 grid points"));
}

TEST(TraceSection, TiltMapGivesTheKnownAngleInDegreesAndTicksAlongTheNormal) {
  const auto s = palp::report::trace_section(rt::known_trace());
  const json& spec = s.figures[1].spec;
  EXPECT_EQ(spec["legends"][0]["title"], "tilt (deg)");
  for (const auto& x : data_values(spec, "cells")) {
    if (x["value"].is_null()) continue;
    EXPECT_NEAR(x["value"].get<double>(), rt::kTraceTiltDeg, 1e-9);
    EXPECT_LT(x["dx_px"].get<double>(), 0.0);  // the normal leans towards −x
    EXPECT_NEAR(x["dy_px"].get<double>(), 0.0, 1e-12);
  }
}

TEST(TraceSection, AGridWithoutCellsOrAPointOutsideItIsRefused) {
  palp::TracedSurface empty;
  empty.plan_name = "none";
  EXPECT_THROW(palp::report::trace_section(empty), palp::ConfigError);
  auto s = rt::known_trace();
  s.points[3].column = 9;
  try {
    palp::report::trace_section(s);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("column 9, outside its 4 x 5 grid"));
  }
}

}  // namespace
