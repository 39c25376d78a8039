// SPDX-License-Identifier: Apache-2.0
// The tidy CSV (palp/tidy_csv.hpp, docs/result-format.md "The tidy CSV"): exact bytes for a
// synthetic 2 x 2 map of known stiffnesses, one row per point and repetition, every key of a
// repetition's summary a column, damaged and missing points kept with their reason, and the
// writer's refusals.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/tidy_csv.hpp"
#include "synth_map.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

/// RFC 4180 records (fields unquoted), enough for what the tidy CSV holds.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char ch = text[k];
    std::string& field = rows.back().back();
    if (quoted) {
      if (ch == '"' && k + 1 < text.size() && text[k + 1] == '"') {
        field += '"';
        ++k;
      } else if (ch == '"') {
        quoted = false;
      } else {
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      rows.back().emplace_back();
    } else if (ch == '\n') {
      rows.emplace_back(1);
    } else {
      field += ch;
    }
  }
  if (rows.back().size() == 1 && rows.back().front().empty()) rows.pop_back();
  return rows;
}

std::size_t column_index(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return k;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

class TidyCsv : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("palp-tidy-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(TidyCsv, MapOf2x2With2RepsIsExactlyTheGoldenBytes) {
  palp::test::write_synth_map(root_ / "map", 2, 2, 2);
  const std::string csv = palp::tidy_csv(root_ / "map");
  const fs::path golden = fs::path(PALP_SOURCE_DIR) / "tests/host/unit/golden/tidy_map_2x2x2.csv";
  if (std::getenv("PALP_WRITE_GOLDEN") != nullptr) write_file(golden, csv);
  if (csv != read_file(golden)) {
    write_file(root_.parent_path() / "tidy_map_2x2x2.actual.csv", csv);
    FAIL() << "differs from " << golden << "; written: " << root_.parent_path() / "tidy_map_2x2x2.actual.csv";
  }
}

TEST_F(TidyCsv, EveryRowIsAPointsRepetitionWithItsKnownStiffness) {
  palp::test::write_synth_map(root_ / "map", 2, 2, 2);
  palp::TidyCsvExport e;
  const auto rows = parse_csv(palp::tidy_csv(root_ / "map", &e));
  EXPECT_EQ(e.rows, 8u);
  EXPECT_EQ(e.points, 4u);
  EXPECT_TRUE(e.damaged.empty());
  ASSERT_EQ(rows.size(), 9u);  // the header and 2 x 2 points x 2 repetitions
  const auto& h = rows.front();
  EXPECT_EQ(h, palp::tidy_csv_columns(palp::IndentationSettings::preset(palp::IndentationPreset::two_d).analysis));
  const std::size_t kfd = column_index(h, "k_fd_N_per_mm"), klin = column_index(h, "k_linear_N_per_mm"),
                    kat1 = column_index(h, "k_at_depth_1_mm_N_per_mm"), model = column_index(h, "model_by_aic"),
                    x = column_index(h, "x_mm"), y = column_index(h, "y_mm");
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const auto& r = rows[n];
    ASSERT_EQ(r.size(), h.size()) << "row " << n;
    const int row = static_cast<int>(n - 1) / 4 + 1, column = static_cast<int>(n - 1) / 2 % 2 + 1;
    EXPECT_EQ(r[0], std::to_string(row));
    EXPECT_EQ(r[1], std::to_string(column));
    EXPECT_EQ(r[2], std::to_string((n - 1) % 2));  // rep as the recording numbers it
    EXPECT_EQ(r[6], "");                           // point_reason
    const double k_N_per_mm = palp::test::synth_k_N_per_m(row, column) * 1e-3;
    EXPECT_NEAR(std::stod(r[kfd]), k_N_per_mm, 0.02 * k_N_per_mm) << "row " << n;
    EXPECT_NEAR(std::stod(r[klin]), k_N_per_mm, 0.005 * k_N_per_mm) << "row " << n;
    if (row == 2 && column == 2) {  // 3 N/mm: the ramp's top force reaches 0.96 mm only
      EXPECT_EQ(r[kat1], "");
      EXPECT_EQ(r[kat1 + 1].rfind("depth 1 mm, beyond the deepest loading sample (0.9586", 0), 0u) << r[kat1 + 1];
    } else {
      EXPECT_NEAR(std::stod(r[kat1]), k_N_per_mm, 0.005 * k_N_per_mm) << "row " << n;
    }
    EXPECT_EQ(r[model], "linear");
    EXPECT_NEAR(std::stod(r[x]), 10.0 * column, 1e-9);  // the touch's x, y in the work object (mm)
    EXPECT_NEAR(std::stod(r[y]), 20.0 * row, 1e-9);
  }
}

TEST_F(TidyCsv, ColumnsHoldEveryKeyOfARepetitionsSummaryButTheModelFreeStandardErrors) {
  const palp::IndentationRun run = palp::test::synth_linear_run(2e3, 12e-3, 2);
  ASSERT_TRUE(run.repetitions);
  const json j = palp::indentation_summary_json(run.repetitions->per_rep[0], nullptr, run.settings.analysis);
  const std::vector<std::string> columns = palp::tidy_csv_columns(run.settings.analysis);
  const auto has = [&](const std::string& c) { return std::find(columns.begin(), columns.end(), c) != columns.end(); };
  int checked = 0;
  for (const auto& [key, value] : j.items()) {
    if (key == "params" || key.ends_with("_reason")) continue;
    if (key == "k_fd_N_per_mm_se" || key == "k_ls_window_N_per_mm_se" || key == "k_fd_paper_N_per_mm_se") {
      EXPECT_TRUE(value.is_null()) << key << " is model-free, so always null";
      EXPECT_FALSE(has(key));
      continue;
    }
    if (value.is_object()) {  // k_at_depth_N_per_mm{,_se}: {"1_mm": ...}
      const std::string tail = key.substr(std::string("k_at_depth").size());  // "_N_per_mm[_se]"
      for (const auto& [depth, v] : value.items()) {
        if (depth.ends_with("_reason")) continue;
        EXPECT_TRUE(has("k_at_depth_" + depth + tail)) << key << "." << depth;
        ++checked;
      }
      continue;
    }
    EXPECT_TRUE(has(key)) << key;
    if (!value.is_boolean() && key != "F0_N" && key.rfind("n_", 0) != 0) {
      EXPECT_TRUE(has(key + "_reason")) << key;
    }
    ++checked;
  }
  EXPECT_GE(checked, 38);  // 30 keys and 2 x 4 tangent depths
}

TEST_F(TidyCsv, ADamagedPointKeepsOneRowWithTheReadersErrorAndTheExportGoesOn) {
  palp::test::write_synth_map(root_ / "map", 2, 2, 2);
  fs::remove(root_ / "map/points/r1_c2/result.json");
  palp::TidyCsvExport e;
  const auto rows = parse_csv(palp::tidy_csv(root_ / "map", &e));
  const std::string error = (root_ / "map/points/r1_c2/result.json").string() + ": no result.json: not a result directory (or unreadable)";
  ASSERT_EQ(e.damaged, std::vector<std::string>{error});
  ASSERT_EQ(rows.size(), 1u + 2 + 1 + 2 + 2);
  EXPECT_EQ(e.rows, 7u);
  const auto& r = rows[3];  // r1_c1's two repetitions, then r1_c2
  EXPECT_EQ(r[0], "1");
  EXPECT_EQ(r[1], "2");
  EXPECT_EQ(r[2], "");
  EXPECT_EQ(r[3], "20");  // the touch is still known
  EXPECT_EQ(r[6], error);
  EXPECT_EQ(r[column_index(rows[0], "k_fd_N_per_mm")], "");
  EXPECT_EQ(rows[4][0] + rows[4][1] + rows[4][2], "210");  // r2_c1 rep 0 follows
}

TEST_F(TidyCsv, AGarbledRecordingIsADamagedPointNamingTheFileAndLine) {
  palp::test::write_synth_map(root_ / "map", 2, 2, 1);
  const fs::path csv = root_ / "map/points/r2_c2/indentation.csv";
  std::string text = read_file(csv);
  const std::size_t line2 = text.find('\n') + 1;
  text.replace(line2, text.find(',', line2) - line2, "nan");
  write_file(csv, text);
  palp::TidyCsvExport e;
  const auto rows = parse_csv(palp::tidy_csv(root_ / "map", &e));
  ASSERT_EQ(e.damaged.size(), 1u);
  EXPECT_NE(e.damaged[0].find(csv.string()), std::string::npos) << e.damaged[0];
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[4][6], e.damaged[0]);
}

TEST_F(TidyCsv, UnmappedAndNotIndentedPointsGetOneRowWithTheirReason) {
  palp::StiffnessMap m = palp::test::write_synth_map(root_ / "map", 2, 2, 2);
  m.points[1].indented = false;
  m.points[1].reason = "no contact within 15.000 mm of travel";
  m.points.resize(3);
  m.surface.points.resize(3);
  m.resume_index = m.surface.resume_index = 3;
  m.complete = m.surface.complete = false;
  m.stopped_because = "cancelled";
  palp::save_map(root_ / "map", m);
  const auto rows = parse_csv(palp::tidy_csv(root_ / "map"));
  ASSERT_EQ(rows.size(), 1u + 2 + 1 + 2 + 1);
  EXPECT_EQ(rows[3][0] + rows[3][1] + rows[3][2] + "|" + rows[3][6], "12|no contact within 15.000 mm of travel");
  EXPECT_EQ(rows[6][0] + rows[6][1] + rows[6][2] + "|" + rows[6][3] + "|" + rows[6][6],
            "22||not mapped: the map stopped before this point (cancelled)");
}

TEST_F(TidyCsv, AResultDirectoryGivesItsRepetitionsWithoutRowColumnOrPosition) {
  palp::write_result(root_ / "one", palp::test::synth_linear_run(1.5e3, 12e-3, 3));
  palp::TidyCsvExport e;
  const auto rows = parse_csv(palp::tidy_csv(root_ / "one", &e));
  EXPECT_EQ(e.points, 1u);
  ASSERT_EQ(rows.size(), 4u);
  for (std::size_t n = 1; n < 4; ++n) {
    EXPECT_EQ(rows[n][0] + rows[n][1] + "|" + rows[n][2] + "|" + rows[n][3] + rows[n][4] + rows[n][5],
              "|" + std::to_string(n - 1) + "|");
    EXPECT_NEAR(std::stod(rows[n][column_index(rows[0], "k_fd_N_per_mm")]), 1.5, 0.03);
  }
}

TEST_F(TidyCsv, InputThatIsNeitherAMapNorAResultIsRefusedWithItsPath) {
  fs::create_directories(root_ / "empty");
  const auto message = [](const fs::path& p) {
    try {
      palp::tidy_csv(p);
    } catch (const palp::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no ConfigError");
  };
  const std::string kinds = "a map directory (with map.json) or a result directory (with result.json)";
  EXPECT_EQ(message(root_ / "empty"),
            (root_ / "empty").string() + " is neither a map directory (no map.json) nor a result directory (no result.json)");
  EXPECT_EQ(message(root_ / "gone"), (root_ / "gone").string() + ": no such directory; give " + kinds);
  write_file(root_ / "file", "x");
  EXPECT_EQ(message(root_ / "file"), (root_ / "file").string() + " is not a directory; give " + kinds);
}

TEST_F(TidyCsv, TheWriterReplacesOnlyATidyCsvPalpWroteAndLeavesNoTemporaryFile) {
  palp::write_result(root_ / "one", palp::test::synth_linear_run(1.5e3, 12e-3, 1));
  const fs::path out = root_ / "out" / "one.csv";
  const palp::TidyCsvExport e = palp::export_tidy_csv(root_ / "one", out);
  EXPECT_EQ(e.rows, 1u);
  const std::string written = read_file(out);
  EXPECT_EQ(written, palp::tidy_csv(root_ / "one"));
  try {
    palp::export_tidy_csv(root_ / "one", out);
    ADD_FAILURE() << "replaced without Overwrite::yes";
  } catch (const palp::ConfigError& x) {
    EXPECT_EQ(std::string(x.what()), out.string() + " already exists; choose another file, or overwrite it (palpctl --overwrite)");
  }
  EXPECT_NO_THROW(palp::export_tidy_csv(root_ / "one", out, palp::Overwrite::yes));  // palp's own: replaced
  const fs::path notes = root_ / "out" / "notes.csv";
  write_file(notes, "row,column,rep\n1,2,3\n");
  try {
    palp::export_tidy_csv(root_ / "one", notes, palp::Overwrite::yes);
    ADD_FAILURE() << "replaced a file palp did not write";
  } catch (const palp::ConfigError& x) {
    EXPECT_EQ(std::string(x.what()), notes.string() +
                                         " was not written by palp (its first line does not begin \"row,column,rep,x_mm,"
                                         "y_mm,z_mm,point_reason\"): nothing was replaced; move it away, or choose "
                                         "another file");
  }
  EXPECT_EQ(read_file(notes), "row,column,rep\n1,2,3\n");
  std::vector<std::string> names;
  for (const auto& f : fs::directory_iterator(root_ / "out")) names.push_back(f.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"notes.csv", "one.csv"}));
}

}  // namespace
