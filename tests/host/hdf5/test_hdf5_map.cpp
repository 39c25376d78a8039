// SPDX-License-Identifier: Apache-2.0
// Maps and identifications as HDF5 files (palp/hdf5.hpp): a map directory read back whole (map.json,
// every point's result, bit-exact), its analysis and repetitions in the file with known numbers,
// a damaged point kept as such; an identification's response as typed columns read back as
// frf.csv gave it; a damaged or foreign file is one clear error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "hdf5_fixture.hpp"
#include "hdf5_test_support.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"

namespace {

namespace fs = std::filesystem;
using palp_test::edit;
using palp_test::expect_same;
using palp_test::Hdf5;
using testing::HasSubstr;

/// A double attribute of the object at `path` (NaN when it is absent).
double attr(const fs::path& file, const char* path, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  double v = std::nan("");
  if (H5Aexists_by_name(f, path, name, H5P_DEFAULT) > 0) {
    const hid_t a = H5Aopen_by_name(f, path, name, H5P_DEFAULT, H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
  }
  H5Fclose(f);
  return v;
}

/// A float64 dataset's values, row-major.
std::vector<double> doubles(const fs::path& file, const char* path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
  const hid_t s = H5Dget_space(d);
  std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
  if (!v.empty()) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  return v;
}

void expect_same(const palp::LoadedResult& a, const palp::LoadedResult& b) {
  EXPECT_EQ(a.summary, b.summary);
  EXPECT_EQ(a.experiment, b.experiment);
  ASSERT_EQ(a.recordings.size(), b.recordings.size());
  for (std::size_t k = 0; k < a.recordings.size(); ++k) {
    EXPECT_EQ(a.recordings[k].first, b.recordings[k].first);
    expect_same(a.recordings[k].second, b.recordings[k].second);
  }
}

std::string map_read_error(const fs::path& p) {
  try {
    (void)palp::read_map_hdf5(p);
  } catch (const palp::RecordingError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(Hdf5, MapReadsBackAsTheSameMapAndPointResultsBitExact) {
  const palp::LoadedMap dir = palp_test::known_map(dir_ / "map");
  ASSERT_EQ(dir.results.size(), 2u);
  palp::write_map_hdf5(dir_ / "map.h5", dir);
  EXPECT_EQ(palp::hdf5_content(dir_ / "map.h5"), "map");
  const palp::LoadedMap back = palp::read_map_hdf5(dir_ / "map.h5");
  EXPECT_EQ(back.document, dir.document);  // map.json's numbers exactly
  EXPECT_EQ(palp::map_to_json(back.map), palp::map_to_json(dir.map));
  EXPECT_FALSE(back.map.complete);
  EXPECT_EQ(back.map.points[1].reason, "no contact");
  ASSERT_EQ(back.results.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.results[k].first, dir.results[k].first);
    expect_same(back.results[k].second, dir.results[k].second);
  }
  EXPECT_TRUE(back.damaged.empty());
  // re-analysed from the file: the numbers the directory gives
  const palp::IndentationRun a = palp::indentation_run_of(dir.results[1].second);
  const palp::IndentationRun b = palp::indentation_run_of(back.results[1].second);
  ASSERT_TRUE(a.analysis && b.analysis);
  EXPECT_EQ(*b.analysis->k_fd_N_per_m.value, *a.analysis->k_fd_N_per_m.value);
}

TEST_F(Hdf5, MapFileHoldsTheKnownAnalysisGridAndLines) {
  palp::write_map_hdf5(dir_ / "map.h5", palp_test::known_map(dir_ / "map"));
  const fs::path f = dir_ / "map.h5";
  const std::vector<double> k = doubles(f, "/map/analysis/k_fd_N_per_mm");
  ASSERT_EQ(k.size(), 4u);
  EXPECT_EQ(k[0], 0.5);
  EXPECT_TRUE(std::isnan(k[1]));
  EXPECT_EQ(k[2], 0.25);
  EXPECT_TRUE(std::isnan(k[3]));
  EXPECT_EQ(doubles(f, "/map/analysis/row_mean_N_per_mm"), (std::vector<double>{0.5, 0.25}));
  // points 1..3 measured (r1_c2 without a stiffness), r2_c2 never: the mask tells the NaNs apart
  EXPECT_EQ(doubles(f, "/map/analysis/measured"), (std::vector<double>{1, 1, 1, 0}));
  EXPECT_EQ(attr(f, "/map/analysis", "median_N_per_mm"), 0.5);
  EXPECT_EQ(attr(f, "/map/points/r1_c1", "k_fd_N_per_mm"), 0.5);
  EXPECT_EQ(attr(f, "/map/points/r1_c2", "indented"), 0.0);
}

TEST_F(Hdf5, EachRepetitionIsAGroupWithItsRowsAndItsOwnNumbers) {
  const palp::LoadedMap dir = palp_test::known_map(dir_ / "map");
  palp::write_map_hdf5(dir_ / "map.h5", dir);
  const palp::IndentationRun run = palp::indentation_run_of(dir.results[0].second);
  ASSERT_TRUE(run.repetitions);
  ASSERT_EQ(run.repetitions->per_rep.size(), 2u);
  const std::vector<int>& rep = run.recording.rep;
  const auto first_of_rep1 = static_cast<double>(std::find(rep.begin(), rep.end(), 1) - rep.begin());
  const fs::path f = dir_ / "map.h5";
  EXPECT_EQ(attr(f, "/map/points/r1_c1/repetitions/rep0", "first_row"), 0.0);
  EXPECT_EQ(attr(f, "/map/points/r1_c1/repetitions/rep0", "rows"), first_of_rep1);
  EXPECT_EQ(attr(f, "/map/points/r1_c1/repetitions/rep1", "first_row"), first_of_rep1);
  EXPECT_EQ(attr(f, "/map/points/r1_c1/repetitions/rep1", "rows"), static_cast<double>(rep.size()) - first_of_rep1);
  for (int k = 0; k < 2; ++k) {
    const std::string path = "/map/points/r1_c1/repetitions/rep" + std::to_string(k);
    const nlohmann::json alone = palp::indentation_summary_json(run.repetitions->per_rep[k], nullptr, run.settings.analysis);
    ASSERT_TRUE(alone["E_star_hertz_Pa"].is_number()) << alone.dump();
    EXPECT_EQ(attr(f, path.c_str(), "E_star_hertz_Pa"), alone["E_star_hertz_Pa"].get<double>()) << k;
    EXPECT_EQ(attr(f, path.c_str(), "delta0_mm"), alone["delta0_mm"].get<double>()) << k;
    EXPECT_EQ(attr(f, path.c_str(), "rep"), k);
  }
  // a result file has them too
  palp::write_result_hdf5(dir_ / "r.h5", dir.results[0].second);
  EXPECT_EQ(attr(dir_ / "r.h5", "/result/repetitions/rep1", "first_row"), first_of_rep1);
}

TEST_F(Hdf5, MapWithADeletedPointKeepsTheOthersAndSaysWhichIsLost) {
  palp_test::known_map(dir_ / "map");
  fs::remove_all(dir_ / "map" / "points" / "r2_c1");
  const palp::LoadedMap dir = palp::load_map_results(dir_ / "map");
  ASSERT_EQ(dir.damaged.size(), 1u);
  EXPECT_EQ(dir.damaged[0].first, "points/r2_c1");
  EXPECT_THAT(dir.damaged[0].second, HasSubstr("result.json"));
  palp::write_map_hdf5(dir_ / "map.h5", dir);
  const palp::LoadedMap back = palp::read_map_hdf5(dir_ / "map.h5");
  ASSERT_EQ(back.results.size(), 1u);
  EXPECT_EQ(back.results[0].first, "points/r1_c1");
  EXPECT_EQ(back.damaged, dir.damaged);
  EXPECT_EQ(palp::map_to_json(back.map), palp::map_to_json(dir.map));
}

TEST_F(Hdf5, DamagedMapFilesAreOneClearError) {
  palp::write_map_hdf5(dir_ / "good.h5", palp_test::known_map(dir_ / "map"));
  const auto copy = [&](const std::string& name) {
    fs::copy_file(dir_ / "good.h5", dir_ / name);
    return dir_ / name;
  };
  EXPECT_THAT(map_read_error(dir_ / "map" / "points" / "r1_c1" / "indentation.csv"), HasSubstr("not an HDF5 file"));
  palp::write_recording_hdf5(dir_ / "rec.h5", palp_test::known_recording());
  EXPECT_THAT(map_read_error(dir_ / "rec.h5"), HasSubstr("holds a recording, not a map"));

  const fs::path no_point = copy("no_point.h5");
  edit(no_point, [](hid_t f) { H5Ldelete(f, "/map/points/r2_c1", H5P_DEFAULT); });
  EXPECT_THAT(map_read_error(no_point), HasSubstr("/map/points: the group r2_c1 is missing"));

  const fs::path no_json = copy("no_json.h5");
  edit(no_json, [](hid_t f) { H5Adelete_by_name(f, "/map", "map_json", H5P_DEFAULT); });
  EXPECT_THAT(map_read_error(no_json), HasSubstr("/map: the attribute map_json is missing"));

  const fs::path bad_json = copy("bad_json.h5");
  edit(bad_json, [](hid_t f) {
    H5Adelete_by_name(f, "/map", "map_json", H5P_DEFAULT);
    const hid_t g = H5Gopen2(f, "/map", H5P_DEFAULT);
    const hid_t t = H5Tcopy(H5T_C_S1);
    const char text[] = R"({"format": "palp.map/1", "rows": 2, "columns": 2, "points": 7})";
    H5Tset_size(t, sizeof text - 1);
    const hid_t s = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(g, "map_json", t, s, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, text);
    H5Aclose(a);
    H5Sclose(s);
    H5Tclose(t);
    H5Gclose(g);
  });
  EXPECT_THAT(map_read_error(bad_json), HasSubstr("/map/map_json: map.json: surface: not a trace"));

  const fs::path no_z = copy("no_z.h5");
  edit(no_z, [](hid_t f) { H5Ldelete(f, "/map/points/r1_c1/recordings/indentation.csv/z_mm", H5P_DEFAULT); });
  EXPECT_THAT(map_read_error(no_z), HasSubstr("/map/points/r1_c1/recordings/indentation.csv: the dataset z_mm is missing"));

  const fs::path cut = copy("cut.h5");
  fs::resize_file(cut, fs::file_size(cut) / 2);
  EXPECT_THAT(map_read_error(cut), testing::AnyOf(HasSubstr("cannot open it"), HasSubstr("cannot read")));
}

TEST_F(Hdf5, IdentificationReadsBackWithItsResponseAsFrfCsvGaveIt) {
  const palp::LoadedIdentification known = palp_test::known_identification();
  palp::write_identification_hdf5(dir_ / "sweep.h5", known);
  EXPECT_EQ(palp::hdf5_content(dir_ / "sweep.h5"), "identification");
  const palp::LoadedIdentification back = palp::read_identification_hdf5(dir_ / "sweep.h5");
  expect_same(back.result, known.result);
  ASSERT_TRUE(back.frf);
  ASSERT_EQ(back.frf->lines.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(back.frf->lines[k].f_Hz, known.frf->lines[k].f_Hz);
    EXPECT_EQ(back.frf->lines[k].G_m_per_N, known.frf->lines[k].G_m_per_N);
    EXPECT_EQ(back.frf->lines[k].sigma_m_per_N, known.frf->lines[k].sigma_m_per_N);
  }
  EXPECT_EQ(back.frf->method, known.frf->method);
  EXPECT_EQ(back.frf->notes, known.frf->notes);
  EXPECT_EQ(doubles(dir_ / "sweep.h5", "/result/frf/im_m_per_N"), (std::vector<double>{-2e-4, -5e-4, -6e-4}));
  // an indentation is not an identification
  EXPECT_THROW(palp::write_identification_hdf5(dir_ / "x.h5", {palp_test::known_result(), std::nullopt}),
               palp::ConfigError);
}

TEST_F(Hdf5, DamagedIdentificationResponseIsOneClearError) {
  palp::write_identification_hdf5(dir_ / "sweep.h5", palp_test::known_identification());
  edit(dir_ / "sweep.h5", [](hid_t f) {
    H5Ldelete(f, "/result/frf/f_Hz", H5P_DEFAULT);
    const hsize_t n = 3;
    const double v[3] = {10, 40, 20};  // not increasing
    const hid_t s = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(f, "/result/frf/f_Hz", H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(d);
    H5Sclose(s);
  });
  try {
    (void)palp::read_identification_hdf5(dir_ / "sweep.h5");
    ADD_FAILURE() << "a response whose frequencies go back was read";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/result/frf"));
    EXPECT_THAT(e.what(), HasSubstr("increas"));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
  edit(dir_ / "sweep.h5", [](hid_t f) { H5Ldelete(f, "/result/frf/sigma_m_per_N", H5P_DEFAULT); });
  EXPECT_THROW(
      {
        try {
          (void)palp::read_identification_hdf5(dir_ / "sweep.h5");
        } catch (const palp::RecordingError& e) {
          EXPECT_THAT(e.what(), HasSubstr("/result/frf: the dataset sigma_m_per_N is missing"));
          throw;
        }
      },
      palp::RecordingError);
}

}  // namespace
