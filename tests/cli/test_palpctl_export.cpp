// SPDX-License-Identifier: Apache-2.0
// palpctl export --format csv: the tidy CSV of a synthetic map (written by the SDK's own writers,
// known stiffnesses) read back by an independent reader, Debian's Python with its stdlib csv
// module (/usr/bin/python3: the python3 first on PATH may be another), to full precision; the
// refusals with their exact text and exit code; a damaged point named on stderr. --format hdf5:
// results and maps read back with the SDK (tests/host/hdf5 has the independent readers).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/tidy_csv.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "synth_map.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using palpctl::test::palpctl;
using palpctl::test::run_process;

constexpr const char* kPython = "/usr/bin/python3";

// Reads the CSV with csv.reader and prints, as JSON: the header, every row's cells, and the
// k_fd_N_per_mm column as Python floats (json.dumps writes them round-trippably).
constexpr const char* kReader = R"(import csv, json, sys
with open(sys.argv[1], newline='') as f:
    table = list(csv.reader(f))
header, rows = table[0], table[1:]
k = header.index('k_fd_N_per_mm')
print(json.dumps({'header': header, 'rows': rows,
                  'k_fd': [float(r[k]) if r[k] else None for r in rows]}))
)";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class PalpctlExport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("palpctl-export-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// The CSV as Python's csv module reads it.
  json python_reads(const fs::path& csv) {
    if (!fs::exists(kPython)) ADD_FAILURE() << kPython << " is missing (Debian's python3)";
    const auto r = run_process({kPython, "-c", kReader, csv.string()});
    EXPECT_EQ(r.code, 0) << r.err;
    return json::parse(r.out);
  }
  fs::path dir_;
};

TEST_F(PalpctlExport, ASyntheticMapReadsBackInPythonsCsvModuleWithEveryRowAndFullPrecision) {
  const palp::StiffnessMap m = palp::test::write_synth_map(dir_ / "map", 2, 2, 2);
  const fs::path out = dir_ / "map.csv";
  const auto r = palpctl({"export", "--format", "csv", (dir_ / "map").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "wrote " + out.string() + ": 8 rows for 4 points\n");
  EXPECT_EQ(r.err, "");
  const json py = python_reads(out);
  EXPECT_EQ(py["header"].get<std::vector<std::string>>(), palp::tidy_csv_columns(m.settings.analysis));
  ASSERT_EQ(py["rows"].size(), 8u);
  for (std::size_t n = 0; n < 8; ++n) {
    const auto& row = py["rows"][n];
    const int point = static_cast<int>(n / 2), rep = static_cast<int>(n % 2);
    EXPECT_EQ(row[0].get<std::string>() + row[1].get<std::string>() + row[2].get<std::string>(),
              std::to_string(point / 2 + 1) + std::to_string(point % 2 + 1) + std::to_string(rep));
    // the double the SDK computed for this repetition, bit for bit after Python's float()
    const palp::IndentationRun run =
        palp::indentation_run_of(palp::load_result(dir_ / "map" / m.points[static_cast<std::size_t>(point)].result_dir));
    const double want = palp::indentation_summary_json(run.repetitions->per_rep[static_cast<std::size_t>(rep)], nullptr,
                                                       run.settings.analysis)["k_fd_N_per_mm"]
                            .get<double>();
    EXPECT_EQ(py["k_fd"][n].get<double>(), want) << "row " << n;
    const double k_N_per_mm = palp::test::synth_k_N_per_m(point / 2 + 1, point % 2 + 1) * 1e-3;
    EXPECT_NEAR(py["k_fd"][n].get<double>(), k_N_per_mm, 0.02 * k_N_per_mm) << "row " << n;
  }
  EXPECT_EQ(read_file(out), palp::tidy_csv(dir_ / "map"));  // the SDK's table, as it is
}

TEST_F(PalpctlExport, ADamagedPointIsNamedOnStderrItsRowSaysWhyAndAQuotedReasonReadsBackWhole) {
  palp::StiffnessMap m = palp::test::write_synth_map(dir_ / "map", 1, 3, 1);
  m.points[0].indented = false;
  m.points[0].reason = "no contact within 15.000 mm of travel, \"guard\" fired";
  palp::save_map(dir_ / "map", m);
  fs::remove(dir_ / "map/points/r1_c2/result.json");
  const fs::path out = dir_ / "map.csv";
  const auto r = palpctl({"--json", "export", "--format", "csv", "--input", (dir_ / "map").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string error = (dir_ / "map/points/r1_c2/result.json").string() + ": no result.json: not a result directory (or unreadable)";
  EXPECT_EQ(r.err, "palpctl: export: a damaged point (its row gives this in point_reason; the export went on): " +
                       error + "\n");
  const json summary = json::parse(r.out);
  EXPECT_EQ(summary["rows"], 3);
  EXPECT_EQ(summary["points"], 3);
  EXPECT_EQ(summary["damaged"], json::array({error}));
  const json py = python_reads(out);
  ASSERT_EQ(py["rows"].size(), 3u);
  EXPECT_EQ(py["rows"][0][6], "no contact within 15.000 mm of travel, \"guard\" fired");
  EXPECT_EQ(py["rows"][1][6], error);
  EXPECT_TRUE(py["k_fd"][0].is_null());
  EXPECT_TRUE(py["k_fd"][1].is_null());
  EXPECT_NEAR(py["k_fd"][2].get<double>(), 2.5, 0.05);  // r1_c3: 2.5 N/mm
}

#ifdef PALP_HAVE_HDF5
TEST_F(PalpctlExport, Hdf5OfAResultAndOfARecordingReadsBackAsTheSameObjects) {
  palp::write_result(dir_ / "one", palp::test::synth_linear_run(1.5e3, 12e-3, 1));
  const palp::LoadedResult dir = palp::load_result(dir_ / "one");
  auto r = palpctl({"--json", "export", "--format", "hdf5", (dir_ / "one").string(), "--out", (dir_ / "one.h5").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["content"], "result");
  const palp::LoadedResult h5 = palp::read_result_hdf5(dir_ / "one.h5");
  EXPECT_EQ(h5.summary, dir.summary);
  ASSERT_EQ(h5.recordings.size(), 1u);
  EXPECT_EQ(h5.recordings[0].second.z_mm, dir.recordings[0].second.z_mm);

  const std::string csv = (dir_ / "one" / "indentation.csv").string();
  r = palpctl({"export", "--format", "hdf5", csv, "--out", (dir_ / "rec.h5").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const palp::Recording back = palp::read_recording_hdf5(dir_ / "rec.h5");
  EXPECT_EQ(back.i_A, palp::read_recording(csv).i_A);
  EXPECT_EQ(palp::sidecar_to_json(*back.sidecar), palp::sidecar_to_json(*palp::read_recording(csv).sidecar));

  // again without --overwrite: refused, the file kept
  r = palpctl({"export", "--format", "hdf5", csv, "--out", (dir_ / "rec.h5").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("already exists"), std::string::npos) << r.err;
}

TEST_F(PalpctlExport, Hdf5OfAMapReadsBackAsTheMapAndItsPointsAndADeletedPointIsNamed) {
  palp::test::write_synth_map(dir_ / "map", 2, 2, 2);
  const fs::path out = dir_ / "map.h5";
  auto r = palpctl({"export", "--format", "hdf5", (dir_ / "map").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const palp::LoadedMap dir = palp::load_map_results(dir_ / "map");
  const palp::LoadedMap h5 = palp::read_map_hdf5(out);
  EXPECT_EQ(h5.document, dir.document);
  ASSERT_EQ(h5.results.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(h5.results[k].second.summary, dir.results[k].second.summary);
    EXPECT_EQ(h5.results[k].second.recordings[0].second.z_mm, dir.results[k].second.recordings[0].second.z_mm);
  }
  std::size_t samples = 0;
  for (const auto& p : dir.results) samples += p.second.recordings[0].second.size();
  EXPECT_EQ(r.out, "wrote " + out.string() + ": a map of 4 of 4 points (4 with results), " + std::to_string(samples) +
                       " samples (HDF5, docs/hdf5-format.md)\n");
  // palpctl analyze map re-analyses the file to the directory's numbers, byte for byte
  const auto from_dir = palpctl({"--json", "analyze", "map", "--input", (dir_ / "map").string()});
  const auto from_h5 = palpctl({"--json", "analyze", "map", "--input", out.string()});
  ASSERT_EQ(from_h5.code, 0) << from_h5.err;
  EXPECT_EQ(from_h5.out, from_dir.out);
  EXPECT_TRUE(json::parse(from_h5.out)["analysis"]["k_fd_N_per_mm"][1][1].is_number());

  fs::remove_all(dir_ / "map" / "points" / "r1_c2");
  r = palpctl({"--json", "export", "--format", "hdf5", (dir_ / "map").string(), "--out", (dir_ / "lost.h5").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "palpctl: export: a damaged point (the file says so in its group; the export went on): " +
                       (dir_ / "map" / "points" / "r1_c2" / "result.json").string() + ": no such result directory\n");
  EXPECT_EQ(json::parse(r.out)["damaged"], json::array({"points/r1_c2"}));
  EXPECT_EQ(palp::read_map_hdf5(dir_ / "lost.h5").results.size(), 3u);
}

TEST_F(PalpctlExport, Hdf5OfAMapRefusesAnExistingOutBeforeReadingAndAForeignOneAlways) {
  palp::test::write_synth_map(dir_ / "map", 1, 2, 1);
  std::ofstream(dir_ / "notes.h5") << "my notes\n";
  const std::vector<std::string> args = {"export", "--format", "hdf5", (dir_ / "map").string(), "--out",
                                         (dir_ / "notes.h5").string()};
  auto r = palpctl(args);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + (dir_ / "notes.h5").string() +
                       " already exists; choose another --out, or pass --overwrite to replace it\n");
  auto again = args;
  again.push_back("--overwrite");
  r = palpctl(again);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("palp did not write it"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir_ / "notes.h5"), "my notes\n");
}
#endif

TEST_F(PalpctlExport, UnknownFormatsAreRefusedWithExit2AndNothingWritten) {
  palp::write_result(dir_ / "one", palp::test::synth_linear_run(1.5e3, 12e-3, 1));
  const fs::path out = dir_ / "one.xlsx";
  const auto r = palpctl({"export", "--format", "xlsx", (dir_ / "one").string(), "--out", out.string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: --format xlsx: unknown; the formats there are: csv, hdf5\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(PalpctlExport, AnInputThatIsNeitherAMapNorAResultIsRefusedWithExit2) {
  const auto r = palpctl({"export", "--format", "csv", dir_.string(), "--out", (dir_ / "x.csv").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + dir_.string() +
                       " is neither a map directory (no map.json) nor a result directory (no result.json)\n");
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

TEST_F(PalpctlExport, AnExistingOutIsReplacedOnlyWithOverwriteAndOnlyWhenPalpWroteIt) {
  palp::write_result(dir_ / "one", palp::test::synth_linear_run(1.5e3, 12e-3, 1));
  const fs::path out = dir_ / "one.csv";
  const std::vector<std::string> args = {"export", "--format", "csv", (dir_ / "one").string(), "--out", out.string()};
  ASSERT_EQ(palpctl(args).code, 0);
  auto r = palpctl(args);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + out.string() + " already exists; choose another --out, or pass --overwrite to replace it\n");
  auto again = args;
  again.push_back("--overwrite");
  r = palpctl(again);
  EXPECT_EQ(r.code, 0) << r.err;
  std::ofstream(out, std::ios::trunc) << "sample,weight_g\n1,2\n";
  r = palpctl(again);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "palpctl: " + out.string() +
                       " was not written by palp (its first line does not begin \"row,column,rep,x_mm,y_mm,z_mm,"
                       "point_reason\"): nothing was replaced; move it away, or choose another file\n");
  EXPECT_EQ(read_file(out), "sample,weight_g\n1,2\n");
}

}  // namespace
