// SPDX-License-Identifier: Apache-2.0
// Recordings and result directories as HDF5 files (palp/hdf5.hpp): read back into the same
// objects, bit-exact; re-analysed to the same numbers as from the directory; written atomically
// and never over a file palp did not write; a damaged or foreign file is one clear error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "hdf5_fixture.hpp"
#include "hdf5_test_support.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"
#include "test_result_synth.hpp"

namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;
using palp_test::Hdf5;
using palp_test::edit;
using palp_test::expect_same;

TEST_F(Hdf5, KnownRecordingReadsBackAsTheSameRecordingBitExact) {
  const palp::Recording known = palp_test::known_recording();
  palp::write_recording_hdf5(dir_ / "run.h5", known);
  const palp::Recording back = palp::read_recording_hdf5(dir_ / "run.h5");
  expect_same(back, known);
  EXPECT_TRUE(std::signbit(back.z_mm[1]));
  EXPECT_EQ(back.z_mm[4], 1.2009999999999998);
  EXPECT_EQ(back.sidecar->extra["specimen"], "insert, position 3");
  EXPECT_EQ(palp::hdf5_content(dir_ / "run.h5"), "recording");
  EXPECT_THAT(files(), testing::ElementsAre("run.h5"));  // no temporary file left
}

TEST_F(Hdf5, CsvRecordingThroughHdf5EqualsTheCsvRead) {
  palp::Recording known = palp_test::known_recording();
  known.sidecar->extra.clear();
  palp::write_recording(dir_ / "run", known);
  const palp::Recording from_csv = palp::read_recording(dir_ / "run.csv");
  ASSERT_TRUE(from_csv.sidecar->csv_crc32);
  palp::write_recording_hdf5(dir_ / "run.h5", from_csv);
  expect_same(palp::read_recording_hdf5(dir_ / "run.h5"), from_csv);  // csv_rows and crc kept
}

TEST_F(Hdf5, SidecarOverTheAttributeHeadersSixtyFourKiBReadsBack) {
  palp::Recording r = palp_test::known_recording();
  r.sidecar->extra["notes"] = std::string(200000, 'x') + "\u00e9";  // and UTF-8
  palp::write_recording_hdf5(dir_ / "run.h5", r);
  expect_same(palp::read_recording_hdf5(dir_ / "run.h5"), r);
}

TEST_F(Hdf5, RecordingWithOnlyTheRequiredColumnsAndNoSidecarStaysSo) {
  palp::Recording r;
  r.sample_index.reset();
  r.i_cmd_A.reset();
  for (auto& p : r.p_Pa) p.reset();
  r.status.reset();
  r.sidecar.reset();
  r.rep_source = palp::RepSource::split_at_current_minima;
  r.ignored_columns = {"temperature_C"};
  for (int k = 0; k < 3; ++k) r.append({.t_s = 0.1 * k, .i_A = 0.5, .z_mm = 1.0 * k, .rep = 0});
  palp::write_recording_hdf5(dir_ / "labview.h5", r);
  const palp::Recording back = palp::read_recording_hdf5(dir_ / "labview.h5");
  expect_same(back, r);
  EXPECT_FALSE(back.status.has_value());
  EXPECT_FALSE(back.sidecar.has_value());
}

TEST_F(Hdf5, ResultFileReanalysesToTheSameNumbersAsItsDirectory) {
  const palp::IndentationRun run = palp_test::synthetic_run();
  ASSERT_TRUE(run.analysis) << run.analysis_reason;
  const palp::LoadedResult from_dir = palp::load_result(palp::write_result(dir_ / "solid-p3", run));
  palp::write_result_hdf5(dir_ / "solid-p3.h5", from_dir);
  const palp::LoadedResult from_h5 = palp::read_result_hdf5(dir_ / "solid-p3.h5");
  EXPECT_EQ(from_h5.summary, from_dir.summary);
  EXPECT_EQ(from_h5.experiment, "indentation");
  ASSERT_EQ(from_h5.recordings.size(), 1u);
  EXPECT_EQ(from_h5.recordings[0].first, "indentation.csv");
  expect_same(from_h5.recordings[0].second, from_dir.recordings[0].second);
  const palp::IndentationRun a = palp::indentation_run_of(from_dir);
  const palp::IndentationRun b = palp::indentation_run_of(from_h5);
  ASSERT_TRUE(a.analysis && b.analysis);
  EXPECT_EQ(palp::indentation_summary_json(*b.analysis, nullptr, b.settings.analysis),
            palp::indentation_summary_json(*a.analysis, nullptr, a.settings.analysis));
  EXPECT_EQ(*b.analysis->delta0_m.value, *run.analysis->delta0_m.value);
  EXPECT_THROW(palp::read_recording_hdf5(dir_ / "solid-p3.h5"), palp::RecordingError);
}

TEST_F(Hdf5, ExistingFileIsRefusedWithoutOverwriteAndAForeignOneEvenWithIt) {
  const palp::Recording known = palp_test::known_recording();
  palp::write_recording_hdf5(dir_ / "run.h5", known);
  EXPECT_THROW(palp::write_recording_hdf5(dir_ / "run.h5", known), palp::ConfigError);
  palp::Recording changed = known;
  changed.i_A[0] = 9.0;
  palp::write_recording_hdf5(dir_ / "run.h5", changed, palp::Overwrite::yes);  // palp's: replaced
  EXPECT_EQ(palp::read_recording_hdf5(dir_ / "run.h5").i_A[0], 9.0);

  { std::ofstream(dir_ / "notes.h5") << "my notes\n"; }
  try {
    palp::write_recording_hdf5(dir_ / "notes.h5", known, palp::Overwrite::yes);
    ADD_FAILURE() << "a file palp did not write was replaced";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("palp did not write it"));
  }
  std::ifstream in(dir_ / "notes.h5");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "my notes\n");
  // an HDF5 file without palp's mark is not palp's either
  palp::write_recording_hdf5(dir_ / "other.h5", known);
  edit(dir_ / "other.h5", [](hid_t f) { H5Adelete(f, "palp_format"); });
  EXPECT_THROW(palp::write_recording_hdf5(dir_ / "other.h5", known, palp::Overwrite::yes), palp::ConfigError);
  EXPECT_THAT(files(), testing::ElementsAre("notes.h5", "other.h5", "run.h5"));
}

TEST_F(Hdf5, BadRecordingIsRefusedAndLeavesNoFile) {
  palp::Recording r = palp_test::known_recording();
  r.i_A[2] = std::nan("");
  EXPECT_THROW(palp::write_recording_hdf5(dir_ / "run.h5", r), palp::ConfigError);
  r = palp_test::known_recording();
  r.z_mm.pop_back();
  EXPECT_THROW(palp::write_recording_hdf5(dir_ / "run.h5", r), palp::ConfigError);
  EXPECT_TRUE(files().empty());
}

TEST_F(Hdf5, DamagedOrForeignFilesAreOneClearError) {
  const fs::path good = dir_ / "good.h5";
  palp::write_recording_hdf5(good, palp_test::known_recording());
  const auto copy = [&](const std::string& name) {
    fs::copy_file(good, dir_ / name);
    return dir_ / name;
  };

  { std::ofstream(dir_ / "text.h5") << "t_s,i_A,z_mm\n"; }
  EXPECT_THAT(read_error(dir_ / "text.h5"), HasSubstr("not an HDF5 file"));
  EXPECT_THAT(read_error(dir_ / "absent.h5"), HasSubstr("no such file"));

  const fs::path cut = copy("cut.h5");
  fs::resize_file(cut, fs::file_size(cut) / 2);
  EXPECT_THAT(read_error(cut), testing::AnyOf(HasSubstr("cannot open it"), HasSubstr("cannot read")));

  const fs::path v2 = copy("v2.h5");
  edit(v2, [](hid_t f) {
    H5Adelete(f, "palp_format");
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 11);
    const hid_t s = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(f, "palp_format", t, s, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, "palp.hdf5/2");
    H5Aclose(a);
    H5Sclose(s);
    H5Tclose(t);
  });
  EXPECT_THAT(read_error(v2), HasSubstr("update the SDK"));

  // a variable-length string (HDF5's global heap, which HDF5 1.10 reads unsafely when damaged)
  const fs::path vl = copy("vl.h5");
  edit(vl, [](hid_t f) {
    H5Adelete_by_name(f, "/recording", "rep_source", H5P_DEFAULT);
    const hid_t g = H5Gopen2(f, "/recording", H5P_DEFAULT);
    const hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    const hid_t s = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(g, "rep_source", t, s, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = "column";
    H5Awrite(a, t, &text);
    H5Aclose(a);
    H5Sclose(s);
    H5Tclose(t);
    H5Gclose(g);
  });
  EXPECT_THAT(read_error(vl), HasSubstr("/recording/rep_source: is not a single fixed-length string"));

  const fs::path no_i = copy("no_i.h5");
  edit(no_i, [](hid_t f) { H5Ldelete(f, "/recording/i_A", H5P_DEFAULT); });
  EXPECT_THAT(read_error(no_i), HasSubstr("/recording: the dataset i_A is missing"));

  const fs::path int_t = copy("int_t.h5");
  edit(int_t, [](hid_t f) {
    H5Ldelete(f, "/recording/t_s", H5P_DEFAULT);
    const hsize_t n = 5;
    const int v[5] = {1, 2, 3, 4, 5};
    const hid_t s = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(f, "/recording/t_s", H5T_STD_I32LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(d);
    H5Sclose(s);
  });
  EXPECT_THAT(read_error(int_t), HasSubstr("/recording/t_s: has the wrong type; palp writes it as float64"));

  const fs::path short_z = copy("short_z.h5");
  edit(short_z, [](hid_t f) {
    H5Ldelete(f, "/recording/z_mm", H5P_DEFAULT);
    const hsize_t n = 4;
    const double v[4] = {1, 2, 3, 4};
    const hid_t s = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(f, "/recording/z_mm", H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(d);
    H5Sclose(s);
  });
  EXPECT_THAT(read_error(short_z), HasSubstr("column z_mm has 4 values where t_s has 5"));

  const fs::path bad_side = copy("bad_side.h5");
  edit(bad_side, [](hid_t f) { H5Adelete_by_name(f, "/recording", "rep_source", H5P_DEFAULT); });
  EXPECT_THAT(read_error(bad_side), HasSubstr("/recording: the attribute rep_source is missing"));
}

}  // namespace
