// SPDX-License-Identifier: Apache-2.0
// The map's report from a known synthetic 9 x 9 map whose columns 2, 5 and 8 are soft
// (report_fixture.hpp): the section marks exactly those columns and embeds every point's values
// and curves; the HTML page is one file with the Vega modules and the specs inside, refuses to
// replace files palp did not write, and says which module file is missing; the SVG files are
// rendered by node-vega with the axes' units; bad inputs get errors that name them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "palp/error.hpp"
#include "palp/map.hpp"
#include "palp/report.hpp"
#include "report_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using palp::report::Report;
using ::testing::HasSubstr;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const palp::report::Figure& figure(const Report& r, const std::string& id) {
  for (const auto& s : r.sections)
    for (const auto& f : s.figures)
      if (f.id == id) return f;
  throw std::runtime_error("no figure " + id);
}

const json& data(const json& spec, const std::string& name) {
  for (const json& d : spec.at("data"))
    if (d.at("name") == name) return d;
  throw std::runtime_error("no data " + name);
}

/// An environment variable set for a scope.
struct ScopedEnv {
  std::string name;
  ScopedEnv(const char* n, const std::string& value) : name(n) { ::setenv(n, value.c_str(), 1); }
  ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

class MapReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("palp-report-test-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    palp::test::write_report_map(root_ / "map");
    report_ = new Report(palp::report::make_report(root_ / "map"));
  }
  static void TearDownTestSuite() {
    delete report_;
    fs::remove_all(root_);
  }
  static fs::path root_;
  static Report* report_;
};
fs::path MapReport::root_;
Report* MapReport::report_ = nullptr;

TEST_F(MapReport, MarksExactlyColumns2_5_8SoftAndNoRow) {
  const Report& r = *report_;
  ASSERT_FALSE(r.sections.empty());
  EXPECT_EQ(r.sections[0].id, "map");
  const json& spec = figure(r, "map-stiffness").spec;
  EXPECT_EQ(data(spec, "soft_columns_data").at("values"), json::parse(R"([{"index": 2}, {"index": 5}, {"index": 8}])"));
  for (const char* none : {"stiff_columns_data", "soft_rows_data", "stiff_rows_data"})
    EXPECT_EQ(data(spec, none).at("values"), json::array()) << none;
  EXPECT_THAT(r.sections[0].text, HasSubstr("Soft columns: 2, 5, 8; stiff columns: none; soft rows: none"));
}

TEST_F(MapReport, EmbedsEveryPointsKnownStiffnessAndCurve) {
  const json& spec = figure(*report_, "map-stiffness").spec;
  const json& points = data(spec, "cells").at("values");
  ASSERT_EQ(points.size(), 81u);
  for (const json& p : points) {
    const int row = p.at("row"), column = p.at("column");
    const double known_N_per_mm = palp::test::report_map_k_N_per_m(row, column) * 1e-3;
    EXPECT_NEAR(p.at("value").get<double>(), known_N_per_mm, 0.03 * known_N_per_mm) << "row " << row << " column " << column;
    EXPECT_TRUE(p.at("delta0").is_number());
  }
  const json& curves = data(spec, "curves").at("values");
  ASSERT_EQ(curves.size(), 81u);  // one repetition per point
  for (const json& c : curves) {
    ASSERT_EQ(c.at("d").size(), c.at("f").size());
    EXPECT_GE(c.at("d").size(), 20u);
    EXPECT_LE(c.at("d").size(), 101u);  // block means, not every sample
  }
  // a linear specimen: at 1 mm the curve's force is k x 1 mm (the largest depth's point near it)
  const json& c = curves[0];
  double best = 1e9, f_at = 0;
  for (std::size_t i = 0; i < c.at("d").size(); ++i)
    if (std::abs(c["d"][i].get<double>() - 1.0) < best) best = std::abs(c["d"][i].get<double>() - 1.0), f_at = c["f"][i];
  ASSERT_LT(best, 0.1);
  EXPECT_NEAR(f_at, palp::test::report_map_k_N_per_m(1, 1) * 1e-3 * 1.0, 0.25);
}

TEST_F(MapReport, HeaderNamesTheDeviceAndTheSettings) {
  std::string text;
  for (const auto& [label, value] : report_->header) text += label + ": " + value + "\n";
  EXPECT_THAT(text, HasSubstr("Device: serial SYNTH-0001, board synthetic"));
  EXPECT_THAT(text, HasSubstr("Firmware: firmware_version 1.0.0"));
  EXPECT_THAT(text, HasSubstr("Grid: 9 rows × 9 columns, 81 of 81 points indented"));
  EXPECT_THAT(text, HasSubstr("Settings: ramp 0.5 → 3 A by 0.01 A every 25 ms, 3 repetitions"));
}

TEST_F(MapReport, HeaderOfAnAdaptiveMapCountsItsMeasuredPointsAgainstTheWholeGrid) {
  // the same map as an adaptive one that measured 30 of its 81 points and spent its budget
  const fs::path dir = root_ / "adaptive-map";
  fs::remove_all(dir);
  fs::copy(root_ / "map", dir, fs::copy_options::recursive);
  palp::StiffnessMap m = palp::load_map(dir);
  m.points.resize(30);
  m.surface.points.resize(30);
  m.resume_index = m.surface.resume_index = 30;
  palp::analysis::AdaptiveGridOptions o;
  o.max_points = 30;
  m.adaptive = o;
  m.adaptive_ended = "budget";
  palp::save_map(dir, m);
  const Report r = palp::report::make_report(dir);
  std::string text;
  for (const auto& [label, value] : r.header) text += label + ": " + value + "\n";
  EXPECT_THAT(text, HasSubstr("Grid: 9 rows × 9 columns, 30 of 81 points indented (adaptive: 30 "
                              "measured, budget 30; ended: budget)"));
}

TEST_F(MapReport, TableMarksTheSoftColumns) {
  const palp::report::Table& t = report_->sections[0].tables.at(0);
  ASSERT_EQ(t.rows.size(), 18u);
  for (int c = 1; c <= 9; ++c)
    EXPECT_EQ(t.rows[static_cast<std::size_t>(c - 1)][3], c == 2 || c == 5 || c == 8 ? "soft" : "") << c;
}

TEST_F(MapReport, HtmlIsOneFileWithTheModulesAndTheSpecs) {
  const fs::path file = root_ / "out" / "map.html";
  palp::report::write_report_html(file, *report_);
  const std::string html = slurp(file);
  EXPECT_EQ(html.rfind(palp::report::kReportHtmlHead, 0), 0u);
  for (const char* module : {"vega-util", "vega-loader", "vega-scenegraph", "vega-selections", "vega-view"})
    EXPECT_THAT(html, HasSubstr("palpVegaModules.next('" + std::string(module) + "')"));
  EXPECT_THAT(html, HasSubstr("<script type=\"application/json\" id=\"spec-map-stiffness\">"));
  EXPECT_THAT(html, Not(HasSubstr("src=\"")));  // nothing loaded from elsewhere
  EXPECT_THAT(html, HasSubstr("<a href=\"#sec-map\">Stiffness map</a>"));
}

TEST_F(MapReport, EmbeddedJsonCannotCloseItsScriptAndReadsBack) {
  Report r;
  r.title = "a </script> title";
  palp::report::Section s;
  s.id = "s";
  s.title = "S";
  s.figures.push_back({"f", "F", "</figcaption>", json{{"text", "</script><!--x-->"}}});
  r.sections.push_back(s);
  const std::string html = palp::report::report_html(r);
  const std::string open = "<script type=\"application/json\" id=\"spec-f\">";
  const std::size_t b = html.find(open) + open.size();
  const std::size_t e = html.find("</script>", b);
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(json::parse(html.substr(b, e - b)), (json{{"text", "</script><!--x-->"}}));
  EXPECT_THAT(html, HasSubstr("<title>a &lt;/script&gt; title</title>"));
  EXPECT_THAT(html, HasSubstr("<figcaption>&lt;/figcaption&gt;</figcaption>"));
}

TEST_F(MapReport, HtmlReplacesOnlyAReportPalpWrote) {
  const fs::path file = root_ / "replace" / "r.html";
  palp::report::write_report_html(file, *report_);
  EXPECT_THROW(palp::report::write_report_html(file, *report_), palp::ConfigError);
  EXPECT_NO_THROW(palp::report::write_report_html(file, *report_, palp::Overwrite::yes));
  const fs::path other = root_ / "replace" / "notes.html";
  std::ofstream(other) << "<!DOCTYPE html>\n<p>my notes</p>\n";
  try {
    palp::report::write_report_html(other, *report_, palp::Overwrite::yes);
    FAIL() << "replaced a file palp did not write";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is not a report palp wrote"));
  }
  EXPECT_EQ(slurp(other), "<!DOCTYPE html>\n<p>my notes</p>\n");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(root_ / "replace")) ++entries;
  EXPECT_EQ(entries, 2u);  // no temporary file left behind
}

TEST_F(MapReport, AMissingVegaModuleIsNamedWithItsPackage) {
  const fs::path empty = root_ / "no-js";
  fs::create_directories(empty);
  const ScopedEnv env("PALP_JS_DIR", empty.string());
  try {
    palp::report::write_report_html(root_ / "never.html", *report_);
    FAIL() << "wrote a page without Vega";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("topojson-client/topojson-client.js"));
    EXPECT_THAT(e.what(), HasSubstr("libjs-vega"));
  }
  EXPECT_FALSE(fs::exists(root_ / "never.html"));
}

TEST_F(MapReport, SvgFilesCarryTheMarksAndTheUnits) {
  const auto files = palp::report::write_report_svgs(root_ / "svg", *report_);
  std::size_t figures = 0;
  for (const auto& s : report_->sections) figures += s.figures.size();
  ASSERT_EQ(files.size(), figures);
  const std::string svg = slurp(root_ / "svg" / "map-stiffness.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  for (const char* text : {"k_fd (N/mm)", "δ (mm)", "F_o (N)", ">soft<", ">column<", ">row<"})
    EXPECT_THAT(svg, HasSubstr(text));
  EXPECT_THROW(palp::report::write_report_svgs(root_ / "svg", *report_), palp::ConfigError);
  EXPECT_NO_THROW(palp::report::write_report_svgs(root_ / "svg", *report_, palp::Overwrite::yes));
}

TEST_F(MapReport, ASpecVegaRefusesFailsWithVegasMessage) {
  Report r;
  palp::report::Section s;
  s.id = "s";
  s.figures.push_back(
      {"bad", "Bad", "", json{{"signals", json::array({{{"name", "a"}, {"update", "nosuchsignal + 1"}}})}}});
  r.sections.push_back(s);
  try {
    palp::report::write_report_svgs(root_ / "bad-svg", r);
    FAIL() << "rendered a bad spec";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.vg.json: Unrecognized signal name: \"nosuchsignal\""));
  }
  EXPECT_FALSE(fs::exists(root_ / "bad-svg"));
}

TEST_F(MapReport, WithoutNodeTheSvgErrorSaysSo) {
  const ScopedEnv env("PALP_NODE", "/nonexistent/node");
  try {
    palp::report::write_report_svgs(root_ / "no-node", *report_);
    FAIL() << "no error without node";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nodejs"));
  }
}

TEST(MakeReport, RefusesWhatIsNotAResult) {
  const fs::path dir = fs::temp_directory_path() / ("palp-report-empty-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  try {
    palp::report::make_report(dir);
    FAIL();
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("neither a map (no map.json), a result (no result.json) nor a trace"));
  }
  try {
    palp::report::make_report(dir / "absent");
    FAIL();
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("absent: no such file or directory"));
  }
  fs::remove_all(dir);
}

}  // namespace
