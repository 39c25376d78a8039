// SPDX-License-Identifier: Apache-2.0
// palpctl report: a synthetic 9 x 9 map (the SDK's own writers; columns 2, 5 and 8 soft) as one
// HTML page and its SVG files, with --json naming them; the page's embedded map marks exactly
// those columns; the refusals (an existing page without --overwrite, a file palp did not write,
// an --svg directory that is not palp's, an input that is no result) with their text and exit 2,
// leaving every file as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/report.hpp"
#include "synth_map.hpp"

namespace palpctl_report_test {  // named: the unity build joins this file with the others
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using palpctl::test::palpctl;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Columns 2, 5, 8: 1.4 N/mm; the others 2.2 N/mm.
double k_N_per_m(int, int column) { return column == 2 || column == 5 || column == 8 ? 1.4e3 : 2.2e3; }

class PalpctlReport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("palpctl-report-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    palp::test::write_synth_map(dir_ / "map", 9, 9, 1, k_N_per_m);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(PalpctlReport, AMapsPageAndSvgMarkColumns2_5_8SoftAndJsonNamesTheFiles) {
  const fs::path html = dir_ / "map.html", svg = dir_ / "svg";
  const auto r = palpctl({"report", (dir_ / "map").string(), "--out", html.string(), "--svg", svg.string(), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.at("html"), html.string());
  // the map, and the surface it was measured on (report-plots' trace section)
  EXPECT_EQ(j.at("svgs"), json::array({(svg / "map-stiffness.svg").string(), (svg / "trace-heights.svg").string(),
                                       (svg / "trace-tilts.svg").string()}));
  ASSERT_EQ(j.at("sections").size(), 2u);
  EXPECT_EQ(j["sections"][0].at("id"), "map");
  EXPECT_EQ(j["sections"][0].at("figures"), json::array({"map-stiffness"}));
  EXPECT_EQ(j["sections"][1].at("figures"), json::array({"trace-heights", "trace-tilts"}));

  const std::string page = read_file(html);
  EXPECT_EQ(page.rfind(palp::report::kReportHtmlHead, 0), 0u);
  const std::string open = "<script type=\"application/json\" id=\"spec-map-stiffness\">";
  const std::size_t b = page.find(open);
  ASSERT_NE(b, std::string::npos);
  const json spec = json::parse(page.substr(b + open.size(), page.find("</script>", b) - b - open.size()));
  json soft_columns, soft_rows;
  for (const json& d : spec.at("data")) {
    if (d.at("name") == "soft_columns_data") soft_columns = d.at("values");
    if (d.at("name") == "soft_rows_data") soft_rows = d.at("values");
  }
  EXPECT_EQ(soft_columns, json::parse(R"([{"index": 2}, {"index": 5}, {"index": 8}])"));
  EXPECT_EQ(soft_rows, json::array());
  EXPECT_EQ(read_file(svg / "map-stiffness.svg").rfind("<svg", 0), 0u);
}

TEST_F(PalpctlReport, RefusesToReplaceWithoutOverwriteOrWhatPalpDidNotWrite) {
  const fs::path html = dir_ / "map.html";
  ASSERT_EQ(palpctl({"report", (dir_ / "map").string(), "--out", html.string()}).code, 0);
  auto r = palpctl({"report", (dir_ / "map").string(), "--out", html.string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + html.string() +
                       " already exists; choose another file, or overwrite it (palpctl --overwrite)\n");
  EXPECT_EQ(palpctl({"report", (dir_ / "map").string(), "--out", html.string(), "--overwrite"}).code, 0);

  const fs::path mine = dir_ / "mine.html";
  std::ofstream(mine) << "<!DOCTYPE html>\n<p>mine</p>\n";
  r = palpctl({"report", (dir_ / "map").string(), "--out", mine.string(), "--overwrite"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is not a report palp wrote"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(mine), "<!DOCTYPE html>\n<p>mine</p>\n");

  const fs::path figures = dir_ / "figures";
  fs::create_directories(figures);
  std::ofstream(figures / "paper.tex") << "\\documentclass{article}\n";
  r = palpctl({"report", (dir_ / "map").string(), "--out", (dir_ / "new.html").string(), "--svg",
               figures.string(), "--overwrite"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not a result directory palp wrote"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "new.html"));  // refused before anything was written
  EXPECT_TRUE(fs::exists(figures / "paper.tex"));
}

TEST_F(PalpctlReport, AnInputThatIsNoResultIsNamed) {
  const auto r = palpctl({"report", (dir_ / "nothing").string(), "--out", (dir_ / "x.html").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + (dir_ / "nothing").string() +
                       ": no such file or directory; give a map directory (map.json), a result directory "
                       "(result.json) or a trace (trace.json)\n");
  EXPECT_FALSE(fs::exists(dir_ / "x.html"));
}

TEST_F(PalpctlReport, AFileThatIsNotPalpsOrAnHdf5ExportIsNamedWithWhatToGive) {
  {
    std::ofstream(dir_ / "notes.txt") << "not json";
    std::ofstream(dir_ / "map.h5", std::ios::binary) << std::string("\x89HDF\r\n\x1a\n", 8) << "rest";
  }
  auto r = palpctl({"report", (dir_ / "notes.txt").string(), "--out", (dir_ / "x.html").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, ::testing::StartsWith("palpctl: " + (dir_ / "notes.txt").string() + ": not JSON ("));
  EXPECT_THAT(r.err, ::testing::EndsWith("; give a map directory (map.json), a result directory (result.json) "
                                         "or a trace (trace.json)\n"));
#if PALP_HAVE_HDF5
  r = palpctl({"report", (dir_ / "map.h5").string(), "--out", (dir_ / "x.html").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + (dir_ / "map.h5").string() +
                       " is an HDF5 file; a report is made from the directory it was exported from (a map, "
                       "result or trace directory)\n");
#endif
  EXPECT_FALSE(fs::exists(dir_ / "x.html"));
}

}  // namespace
}  // namespace palpctl_report_test
