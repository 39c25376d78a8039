// SPDX-License-Identifier: Apache-2.0
// The pressure section's figure and table (host/src/report/pressure_section.cpp) from the known
// run whose channel m reads 20 m Pa per newton of object force: the plotted points and lines
// have those slopes, the Boyle ΔV follows from the rise.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "report/sections.hpp"
#include "report_plots_synth.hpp"
#include "test_result_synth.hpp"

namespace {

using nlohmann::json;
using palp_test::report::data_values;

class PressureSection : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto dir = palp_test::report::fresh_dir("pressure");
    section_ = new palp::report::Section(palp::report::pressure_section(
        palp::load_result(palp_test::report::write_known_indentation(dir / "solid-p3"))));
  }
  static void TearDownTestSuite() { delete section_; }
  static palp::report::Section* section_;
};
palp::report::Section* PressureSection::section_ = nullptr;

TEST_F(PressureSection, EachChannelsPointsAndRegressionLineHaveItsKnownSlope) {
  ASSERT_EQ(section_->figures.size(), 1u);
  const json& spec = section_->figures[0].spec;
  EXPECT_EQ(spec["axes"][0]["title"], "F_o (N)");
  EXPECT_EQ(spec["axes"][1]["title"], "p (Pa)");
  for (int m = 1; m <= 6; ++m) {
    const std::string id = "p" + std::to_string(m);
    const double slope = 20.0 * m;
    const json& pts = data_values(spec, id);
    ASSERT_EQ(pts.size(), 201u) << id;  // 101 loading and 100 unloading levels of 10 mA
    for (const auto& r : pts) {  // F_o from the fitted z_c, within a few mN of the true one
      EXPECT_NEAR(r["p_Pa"].get<double>(), slope * r["F_o_N"].get<double>(), 0.004 * slope) << id;
      // one point per level, the mean of the two identical repetitions: no spread
      EXPECT_NEAR(r["hi_Pa"].get<double>() - r["lo_Pa"].get<double>(), 0.0, 1e-9) << id;
    }
    const json& line = data_values(spec, id + "_fit");
    ASSERT_EQ(line.size(), 2u);
    const double fitted = (line[1]["p_Pa"].get<double>() - line[0]["p_Pa"].get<double>()) /
                          (line[1]["F_o_N"].get<double>() - line[0]["F_o_N"].get<double>());
    EXPECT_NEAR(fitted, slope, 0.01 * slope) << id;
    EXPECT_NEAR(line[1]["F_o_N"].get<double>(), 2.71, 0.01) << id;  // the line spans the data
  }
  const json& legend_domain = spec["scales"][2]["domain"];
  EXPECT_THAT(legend_domain[0].get<std::string>(), testing::StartsWith("p1: 20 Pa/N, R² = "));
  EXPECT_THAT(legend_domain[5].get<std::string>(), testing::StartsWith("p6: 120 Pa/N, R² = "));
}

TEST_F(PressureSection, TheTableGivesTheSlopesAndTheBoyleVolumeOfTheRise) {
  ASSERT_EQ(section_->tables.size(), 1u);
  const auto& t = section_->tables[0];
  ASSERT_EQ(t.rows.size(), 6u);
  EXPECT_EQ(t.columns[7], "ΔV isothermal (mm³)");
  for (std::size_t m = 0; m < 6; ++m) {
    const auto& row = t.rows[m];
    EXPECT_EQ(row[0], "p" + std::to_string(m + 1));
    EXPECT_NEAR(std::stod(row[1]), 20.0 * (m + 1), 0.01 * 20.0 * (m + 1));
    // rise = slope x F_o at the peak (2.71 N); ΔV = V1 (1 - P1 / (P1 + rise)) with the paper's
    // Ø5 x 90 mm channel and 50 cm of 1/16 in tube: V1 = 2757 mm³ (analysis/pressure.hpp)
    const double rise = std::stod(row[5]);
    EXPECT_NEAR(rise, 20.0 * (m + 1) * 2.71, 0.01 * 20.0 * (m + 1) * 2.71);
    EXPECT_NEAR(std::stod(row[7]), 2757.0 * (1.0 - 101325.0 / (101325.0 + rise)), 0.002 * 2757.0 * rise / 101325.0 + 1e-3);
    EXPECT_LT(std::stod(row[8]), std::stod(row[7]));  // the adiabatic bound is smaller
  }
}

TEST(PressureSectionWithoutChannels, GivesTextAndNoFigure) {
  palp::IndentationRun run = palp_test::synthetic_run();
  for (auto& col : run.recording.p_Pa) col.reset();
  palp::analyze_run(run);
  const auto dir = palp_test::report::fresh_dir("pressure-none");
  const auto s = palp::report::pressure_section(palp::load_result(palp::write_result(dir / "r", run)));
  EXPECT_TRUE(s.figures.empty());
  EXPECT_THAT(s.text, testing::HasSubstr("No pressure figure"));
  EXPECT_THAT(s.text, testing::HasSubstr("pressure column"));
}

}  // namespace
