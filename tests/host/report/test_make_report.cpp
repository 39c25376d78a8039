// SPDX-License-Identifier: Apache-2.0
// make_report chooses the builders by what the input is: report-plots' known indentation result
// (result.json's experiment "indentation": the curves and the pressure channels), its known
// identification ("identification") and its known trace (a trace.json file, or the directory
// holding one) each give their sections, a header from result.json and its sidecar, and one
// page with every figure's spec; an experiment without a report is refused by name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/identification.hpp"
#include "palp/result.hpp"
#include "palp/report.hpp"
#include "palp/trace.hpp"
#include "report/report_internal.hpp"
#include "report_plots_synth.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::vector<std::string> section_ids(const palp::report::Report& r) {
  std::vector<std::string> ids;
  for (const auto& s : r.sections) ids.push_back(s.id);
  return ids;
}

std::string header_text(const palp::report::Report& r) {
  std::string text;
  for (const auto& [label, value] : r.header) text += label + ": " + value + "\n";
  return text;
}

/// Every figure of r is on its page, as an embedded spec and a place to draw it.
void expect_every_figure_on_the_page(const palp::report::Report& r) {
  const std::string html = palp::report::report_html(r);
  for (const auto& s : r.sections) {
    EXPECT_THAT(html, HasSubstr("<section id=\"sec-" + s.id + "\">"));
    for (const auto& f : s.figures) {
      EXPECT_THAT(html, HasSubstr("<script type=\"application/json\" id=\"spec-" + f.id + "\">"));
      EXPECT_THAT(html, HasSubstr("data-figure=\"" + f.id + "\""));
    }
  }
}

TEST(MakeReport, AnIndentationResultGivesItsCurvesAndPressures) {
  const fs::path dir = palp_test::report::write_known_indentation(palp_test::report::fresh_dir("mr-indentation") / "result");
  const palp::report::Report r = palp::report::make_report(dir);
  EXPECT_EQ(section_ids(r), (std::vector<std::string>{"indentation", "pressure"}));
  EXPECT_THAT(r.title, HasSubstr("Indentation: "));
  EXPECT_THAT(header_text(r), HasSubstr("Device: serial SIM-0001, board palp-sim"));
  EXPECT_THAT(header_text(r), HasSubstr("Firmware: firmware_version 1.2.3"));
  EXPECT_THAT(header_text(r), HasSubstr("Settings: ramp 0.5 → 1.5 A by 0.01 A every 100 ms, 2 repetitions"));
  EXPECT_FALSE(r.sections[0].figures.empty());
  EXPECT_FALSE(r.sections[1].figures.empty());
  expect_every_figure_on_the_page(r);
  // its result.json's path reads the same
  EXPECT_EQ(section_ids(palp::report::make_report(dir / "result.json")), section_ids(r));
}

TEST(MakeReport, AnIdentificationResultGivesItsBodePlots) {
  const fs::path dir =
      palp_test::report::write_known_identification(palp_test::report::fresh_dir("mr-identification") / "result");
  const palp::report::Report r = palp::report::make_report(dir);
  EXPECT_EQ(section_ids(r), (std::vector<std::string>{"identification"}));
  EXPECT_THAT(r.title, HasSubstr("Identification: "));
  EXPECT_FALSE(r.sections[0].figures.empty());
  expect_every_figure_on_the_page(r);
}

TEST(MakeReport, AnIdentificationsSettingsReadAsKeyValuePairsNotJson) {
  palp::LoadedResult loaded = palp::load_result(
      palp_test::report::write_known_identification(palp_test::report::fresh_dir("mr-id-settings") / "result"));
  loaded.summary["parameters"] = palp::identification_settings_json(palp::IdentificationSettings{});
  std::string settings;
  for (const auto& [key, value] : palp::report::detail::result_header(loaded))
    if (key == "Settings") settings = value;
  EXPECT_THAT(settings, HasSubstr("bias_A 1, "));           // keys carry their units
  EXPECT_THAT(settings, HasSubstr("fit.max_lm_iterations "));  // nested objects dotted
  EXPECT_THAT(settings, ::testing::Not(HasSubstr("{")));
}

TEST(MakeReport, ATraceFileOrItsDirectoryGivesTheSurface) {
  const fs::path dir = palp_test::report::fresh_dir("mr-trace");
  palp::save_trace(dir / "trace.json", palp_test::report::known_trace());
  for (const fs::path& input : {dir / "trace.json", dir}) {
    const palp::report::Report r = palp::report::make_report(input);
    EXPECT_EQ(section_ids(r), (std::vector<std::string>{"trace"})) << input;
    EXPECT_THAT(header_text(r), HasSubstr("Grid: 4 rows × 5 columns, 20 points traced"));
    expect_every_figure_on_the_page(r);
  }
}

TEST(MakeReport, AnExperimentWithoutAReportIsRefusedByName) {
  const fs::path dir = palp_test::report::write_known_indentation(palp_test::report::fresh_dir("mr-other") / "result");
  std::ifstream in(dir / "result.json");
  nlohmann::json j = nlohmann::json::parse(in);
  in.close();
  j["experiment"] = "calibration";
  std::ofstream(dir / "result.json") << j.dump(2);
  try {
    palp::report::make_report(dir);
    FAIL() << "made a report of an unknown experiment";
  } catch (const palp::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("experiment \"calibration\" has no report"));
  }
}

}  // namespace
