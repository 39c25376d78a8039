// SPDX-License-Identifier: Apache-2.0
// The indentation section's figures (host/src/report/indentation_section.cpp) from the known
// Hertz specimen (E* = 125.8 kPa, R = 2.5 mm, K_f = 2.918 N/A, I_c = 0.5 A, bias 1 A,
// k_v = 0.0439 N/mm): the plotted data are that curve, the fits pass through it, δ0 and the
// tangent sit where the Hertz law puts them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "palp/error.hpp"
#include "report/sections.hpp"
#include "report_plots_synth.hpp"
#include "test_result_synth.hpp"

namespace {

using nlohmann::json;
using palp_test::report::data_values;
using palp_test::report::interpolate;

constexpr double kKf = 2.918, kIc = 0.5, kBiasA = 1.0;

// The known object force at a depth (N, m).
double hertz_N(double depth_m) {
  return depth_m > 0 ? 4.0 / 3.0 * palp_test::kEstar * std::sqrt(palp_test::kR) * std::pow(depth_m, 1.5) : 0.0;
}
// The depth where the Hertz force reaches F (m).
double hertz_depth_m(double F_N) {
  return std::pow(F_N / (4.0 / 3.0 * palp_test::kEstar * std::sqrt(palp_test::kR)), 2.0 / 3.0);
}

class IndentationSection : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto dir = palp_test::report::fresh_dir("indentation");
    section_ = new palp::report::Section(palp::report::indentation_section(
        palp::load_result(palp_test::report::write_known_indentation(dir / "solid-p3"))));
  }
  static void TearDownTestSuite() { delete section_; }
  static const json& spec(std::size_t k) { return section_->figures.at(k).spec; }
  static palp::report::Section* section_;
};
palp::report::Section* IndentationSection::section_ = nullptr;

TEST_F(IndentationSection, HasTheForceDepthAndMeanSdFiguresWithUnitAxesAndThePaperTable) {
  ASSERT_EQ(section_->figures.size(), 2u);
  EXPECT_EQ(section_->figures[0].id, "indentation-force-depth");
  EXPECT_EQ(section_->figures[1].id, "indentation-mean-sd");
  for (const auto& f : section_->figures) {
    EXPECT_EQ(f.spec["$schema"], "https://vega.github.io/schema/vega/v5.json");
    EXPECT_GT(f.spec["width"].get<int>(), 0);
    EXPECT_EQ(f.spec["axes"][0]["title"], "δ (mm)");
    EXPECT_EQ(f.spec["axes"][1]["title"], "F_o (N)");
  }
  ASSERT_EQ(section_->tables.size(), 1u);
  EXPECT_THAT(section_->tables[0].columns, testing::ElementsAre("quantity", "unit", "value", "s.e.", "s.d."));
}

TEST_F(IndentationSection, EveryRepetitionsPointsLieOnTheKnownHertzCurve) {
  for (const char* rep : {"rep1", "rep2"}) {
    const json& rows = data_values(spec(0), rep);
    ASSERT_GT(rows.size(), 150u) << rep;  // 101 loading + 100 unloading plateaus
    double deepest = 0;
    for (const auto& r : rows) {
      const double d = r["delta_mm"].get<double>() * 1e-3;
      // z is recorded to 1 µm: F_o within that micrometre's force (and the fitted z_c's error)
      EXPECT_NEAR(r["F_o_N"].get<double>(), hertz_N(d), 3e-3) << rep << " at δ = " << d * 1e3 << " mm";
      deepest = std::max(deepest, d);
    }
    // the top of the ramp: K_f (1.5 A - I_c) = k_v δ + F_o(δ)
    EXPECT_NEAR(deepest * 1e3, 4.71, 0.01) << rep;
  }
}

TEST_F(IndentationSection, TheHertzFitPassesThroughTheKnownForceAndTheLinearFitDoesNot) {
  const json& hertz = data_values(spec(0), "fit_hertz");
  EXPECT_NEAR(interpolate(hertz, "delta_mm", "F_o_N", 2.0), hertz_N(2e-3), 2e-3);  // 0.750 N
  EXPECT_NEAR(interpolate(hertz, "delta_mm", "F_o_N", 4.0), hertz_N(4e-3), 3e-3);
  const json& linear = data_values(spec(0), "fit_linear");
  EXPECT_GT(std::abs(interpolate(linear, "delta_mm", "F_o_N", 2.0) - hertz_N(2e-3)), 0.05);
  // each fit starts at its contact point, marked; Hertz's is the known z_c (depth 0)
  const json& contacts = data_values(spec(0), "contacts");
  ASSERT_EQ(contacts.size(), 3u);
  EXPECT_EQ(contacts[1]["model"], "Hertz fit");
  EXPECT_NEAR(contacts[1]["delta_mm"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(contacts[1]["z_c_mm"].get<double>(), 25.0, 0.005);
  EXPECT_DOUBLE_EQ(contacts[0]["delta_mm"].get<double>(), linear[0]["delta_mm"].get<double>());
}

TEST_F(IndentationSection, Delta0AndTheTangentSitAtTheBiasForceOfTheHertzLaw) {
  const double F0 = kKf * (kBiasA - kIc);
  const double d0 = hertz_depth_m(F0);  // 3.115 mm
  const json& dot = data_values(spec(1), "delta0");
  ASSERT_EQ(dot.size(), 1u);
  EXPECT_DOUBLE_EQ(dot[0]["F_o_N"].get<double>(), F0);
  EXPECT_NEAR(dot[0]["delta_mm"].get<double>(), d0 * 1e3, 0.005);
  const double kt = 1.5 * hertz_N(d0) / d0;  // dF/dδ = 3/2 F/δ for Hertz: 0.702 N/mm
  EXPECT_NEAR(dot[0]["k_t_N_per_mm"].get<double>(), kt * 1e-3, 0.002);
  // the tangent line has that slope and passes through (δ0, F_0)
  const json& t = data_values(spec(1), "tangent");
  const double slope = (t[1]["F_o_N"].get<double>() - t[0]["F_o_N"].get<double>()) /
                       (t[1]["delta_mm"].get<double>() - t[0]["delta_mm"].get<double>());
  EXPECT_NEAR(slope, kt * 1e-3, 0.002);
  EXPECT_NEAR(interpolate(t, "delta_mm", "F_o_N", dot[0]["delta_mm"].get<double>()), F0, 1e-9);
}

TEST_F(IndentationSection, TheMeanOfIdenticalRepetitionsIsTheHertzCurveWithANarrowBand) {
  const json& rows = data_values(spec(1), "mean_sd");
  ASSERT_GT(rows.size(), 100u);
  for (const auto& r : rows) {
    const double d = r["delta_mm"].get<double>() * 1e-3;
    // linear interpolation between the plateaus (0.2 mm apart at first contact) is a chord of the
    // curve: it lies on the curve once the plateaus are close
    if (d >= 0.5e-3) {
      EXPECT_NEAR(r["mean_N"].get<double>(), hertz_N(d), 3e-3) << "at δ = " << d * 1e3 << " mm";
    }
    EXPECT_LE(r["lo_N"].get<double>(), r["mean_N"].get<double>());
    EXPECT_GE(r["hi_N"].get<double>(), r["mean_N"].get<double>());
    EXPECT_LT(r["hi_N"].get<double>() - r["lo_N"].get<double>(), 4e-3);  // the two reps agree
    EXPECT_EQ(r["reps"], 2);
  }
}

TEST_F(IndentationSection, TheTableGivesTheKnownModulusWithItsStandardErrorAndSpread) {
  const auto& rows = section_->tables[0].rows;
  const auto it = std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r[0] == "E* (Hertz fit)"; });
  ASSERT_NE(it, rows.end());
  EXPECT_EQ((*it)[1], "kPa");
  EXPECT_NEAR(std::stod((*it)[2]), palp_test::kEstar * 1e-3, 0.01 * palp_test::kEstar * 1e-3);
  EXPECT_FALSE((*it)[3].empty());  // s.e. of the fit
  const auto d0 = std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r[0] == "δ0 (depth at F_0)"; });
  ASSERT_NE(d0, rows.end());
  EXPECT_NEAR(std::stod((*d0)[2]), hertz_depth_m(kKf * (kBiasA - kIc)) * 1e3, 0.005);
  EXPECT_NE((*d0)[4], "");  // s.d. over the two repetitions
  const auto model = std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r[0] == "model (lowest AIC)"; });
  ASSERT_NE(model, rows.end());
  EXPECT_EQ((*model)[2], "hertz");
}

TEST(IndentationSectionErrors, AnotherExperimentIsRefusedNamingIt) {
  const auto dir = palp_test::report::fresh_dir("indentation-refused");
  const auto loaded = palp::load_result(palp_test::report::write_known_identification(dir / "id"));
  try {
    palp::report::indentation_section(loaded);
    FAIL() << "no RecordingError";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("not an indentation"));
  }
}

}  // namespace

namespace {

TEST(IndentationSectionWithoutFit, GivesTheAnalysisReasonAndTheTableButNoFigure) {
  palp::IndentationRun run = palp_test::synthetic_run();
  for (auto& i : run.recording.i_A) i = 0.3;  // never above I_c = 0.5 A: no contact
  palp::analyze_run(run);
  const auto dir = palp_test::report::fresh_dir("indentation-no-fit");
  const auto s = palp::report::indentation_section(palp::load_result(palp::write_result(dir / "r", run)));
  EXPECT_TRUE(s.figures.empty());
  EXPECT_THAT(s.text, testing::StartsWith("No force–depth figure: "));
  EXPECT_GT(s.text.size(), std::string("No force–depth figure: ").size());  // with the reason
  ASSERT_EQ(s.tables.size(), 1u);
}

}  // namespace
