// SPDX-License-Identifier: Apache-2.0
// read_recording: what it tolerates (tabs, CRLF, comments, a byte order mark, any column order, a
// LabVIEW export of three columns) and, for everything malformed, the exact line and problem.
#include <gtest/gtest.h>

#include <cstdio>

#include "palp/recording.hpp"
#include "test_recording_util.hpp"

using palp::Column;
using palp::read_recording;
using palp::Recording;
using palp::RepSource;
using palp_test::expect_recording_error;
using palp_test::TempDir;
using palp_test::write_text;

namespace {

/// Writes text to dir/run.csv and expects reading it to fail on `line` with `problem`.
void expect_refused(const TempDir& dir, const std::string& text, std::size_t line,
                    const std::string& problem) {
  const auto csv = dir / "run.csv";
  write_text(csv, text);
  expect_recording_error([&] { read_recording(csv); }, csv, line, problem);
}

}  // namespace

// --- accepted -----------------------------------------------------------------------------------

TEST(RecordingReader, TabsCrlfCommentsBlankLinesBomAndAnyColumnOrderAreAccepted) {
  TempDir dir;
  const auto csv = dir / "run.csv";
  write_text(csv,
             "\xEF\xBB\xBF# exported by hand\r\n"
             "z_mm\tsample_index\ti_A\textra col\tt_s\r\n"
             "\r\n"
             "0.25\t7\t0.5\tfoo\t0\r\n"
             "  # a comment between rows\r\n"
             " 0.5 \t8\t+0.75\tbar\t0.001\r\n"
             "1e-3\t9\t1.0\tbaz\t0.001");  // equal times, no line end at the end
  const Recording r = read_recording(csv);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r.t_s, (std::vector<double>{0, 0.001, 0.001}));
  EXPECT_EQ(r.i_A, (std::vector<double>{0.5, 0.75, 1.0}));
  EXPECT_EQ(r.z_mm, (std::vector<double>{0.25, 0.5, 0.001}));
  ASSERT_TRUE(r.sample_index);
  EXPECT_EQ(*r.sample_index, (std::vector<std::uint64_t>{7, 8, 9}));
  EXPECT_FALSE(r.i_cmd_A);
  EXPECT_FALSE(r.status);
  for (const auto& p : r.p_Pa) EXPECT_FALSE(p);
  EXPECT_EQ(r.ignored_columns, (std::vector<std::string>{"extra col"}));
  EXPECT_EQ(r.rep_source, RepSource::split_at_current_minima);
  EXPECT_EQ(r.rep, (std::vector<int>{0, 0, 0}));
  EXPECT_FALSE(r.sidecar);
  EXPECT_EQ(r.columns(), palp::ColumnSet::required().with(Column::sample_index).with(Column::rep));
}

TEST(RecordingReader, WholeNumberColumnsAcceptWholeNumbersWrittenAsDecimals) {
  TempDir dir;
  const auto csv = dir / "run.csv";
  write_text(csv, "t_s,i_A,z_mm,status,rep,sample_index\n0,1,0,3.0,1e0,+5\n0,1,0,65535,-1,0\n");
  const Recording r = read_recording(csv);
  EXPECT_EQ(*r.status, (std::vector<std::uint16_t>{3, 65535}));
  EXPECT_EQ(r.rep, (std::vector<int>{1, -1}));
  EXPECT_EQ(r.rep_source, RepSource::column);
  EXPECT_EQ(*r.sample_index, (std::vector<std::uint64_t>{5, 0}));
}

TEST(RecordingReader, LabviewExportOfThreeColumnsLoadsAndIsSplitIntoItsThreeRepetitions) {
  TempDir dir;
  std::vector<std::size_t> starts;
  const std::vector<double> i_A = palp_test::staircase(0.25, 20, 3, 0.002, starts);
  std::string text = "# LabVIEW measurement, reduced to t_s, i_A, z_mm\r\nt_s\ti_A\tz_mm\r\n";
  char line[128];
  for (std::size_t k = 0; k < i_A.size(); ++k) {
    std::snprintf(line, sizeof line, "%.6f\t%.6f\t%.6f\r\n", static_cast<double>(k) * 0.025, i_A[k],
                  2.0 * (i_A[k] - 0.5));
    text += line;
  }
  const auto csv = dir / "labview.csv";
  write_text(csv, text);

  const Recording r = read_recording(csv);
  ASSERT_EQ(r.size(), i_A.size());
  EXPECT_EQ(r.rep_source, RepSource::split_at_current_minima);
  EXPECT_FALSE(r.sidecar);
  EXPECT_FALSE(r.sample_index);
  EXPECT_EQ(r.rep.front(), 0);
  EXPECT_EQ(r.rep.back(), 2);
  for (std::size_t k = 0; k < r.size(); ++k) {
    const int expected = k >= starts[2] ? 2 : k >= starts[1] ? 1 : 0;
    ASSERT_EQ(r.rep[k], expected) << "sample " << k;
  }
}

// --- refused, with the line and the problem ------------------------------------------------------

TEST(RecordingReader, DecimalCommaInATabSeparatedFileIsNamedWithItsFix) {
  TempDir dir;
  expect_refused(dir, "t_s\ti_A\tz_mm\n0\t0.5\t0\n0.001\t1,5\t0.1\n", 3,
                 "column i_A: \"1,5\" has a decimal comma; numbers need a decimal point (1.5)");
}

TEST(RecordingReader, DecimalCommaInACommaSeparatedFileShowsAsTooManyFields) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm\n0,0.5,0\n0.001,1,5,0.1\n", 3,
                 "4 fields where the header has 3 (a decimal comma? numbers need a decimal point)");
}

TEST(RecordingReader, RowWithTooFewFieldsIsRefused) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm\r\n0,0.5,0\r\n0.1,1\r\n", 3, "2 fields where the header has 3");
}

TEST(RecordingReader, MissingRequiredColumnIsNamed) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,p1_Pa\n0,1,2\n", 1,
                 "the header lacks the required column z_mm; a recording needs t_s, i_A and z_mm "
                 "(the header has: t_s, i_A, p1_Pa)");
  expect_refused(dir, "# two missing\ntime\ti_A\n0\t1\n", 2,
                 "the header lacks the required columns t_s, z_mm; a recording needs t_s, i_A "
                 "and z_mm (the header has: time, i_A)");
}

TEST(RecordingReader, SemicolonSeparatedFileGetsAHint) {
  TempDir dir;
  expect_refused(dir, "t_s;i_A;z_mm\n0;1,5;2\n", 1,
                 "the header lacks the required columns t_s, i_A, z_mm; a recording needs t_s, "
                 "i_A and z_mm (the header has: t_s;i_A;z_mm); the columns look separated by "
                 "semicolons, but a recording uses commas or tabs");
}

TEST(RecordingReader, RepeatedColumnIsRefused) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm,i_A\n0,1,2,3\n", 1,
                 "the column i_A appears twice in the header");
}

TEST(RecordingReader, NonNumberNamesTheColumnAndTheText) {
  TempDir dir;
  expect_refused(dir, "# comment\nt_s,i_A,z_mm\n0,0.5,0\n0.1,0.6,abc\n", 4,
                 "column z_mm: \"abc\" is not a number");
  expect_refused(dir, "t_s,i_A,z_mm\n0,0.5,1e\n", 2, "column z_mm: \"1e\" is not a number");
  expect_refused(dir, "t_s,i_A,z_mm\n0,0x10,0\n", 2, "column i_A: \"0x10\" is not a number");
}

TEST(RecordingReader, NanAndInfinityAreNotNumbers) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm\n0,nan,0\n", 2, "column i_A: \"nan\" is not a number");
  expect_refused(dir, "t_s,i_A,z_mm\n0,1,-inf\n", 2, "column z_mm: \"-inf\" is not a number");
  expect_refused(dir, "t_s,i_A,z_mm\n0,1,0\n1,1,1e999\n", 3,
                 "column z_mm: \"1e999\" is out of range (beyond a double)");
}

TEST(RecordingReader, WholeNumberColumnsRefuseFractionsAndOutOfRangeValues) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm,status\n0,1,0,1.5\n", 2,
                 "column status: \"1.5\" is not a whole number");
  expect_refused(dir, "t_s,i_A,z_mm,status\n0,1,0,70000\n", 2,
                 "column status: \"70000\" is out of range (0 to 65535)");
  expect_refused(dir, "t_s,i_A,z_mm,sample_index\n0,1,0,-1\n", 2,
                 "column sample_index: \"-1\" is out of range (0 to 18446744073709551615)");
}

TEST(RecordingReader, EmptyCellIsRefused) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm\n0,1,0\n0.1, ,0\n", 3, "column i_A is empty");
}

TEST(RecordingReader, DecreasingTimeNamesBothValues) {
  TempDir dir;
  expect_refused(dir, "t_s,i_A,z_mm\n0.1,1,0\n0.2,1,0\n0.15,1,0\n", 4,
                 "t_s decreases from 0.2 to 0.15; it must not decrease");
}

TEST(RecordingReader, EmptyFileIsRefused) {
  TempDir dir;
  expect_refused(dir, "", 0,
                 "the file is empty; a recording starts with a header row naming its columns "
                 "(t_s, i_A, z_mm)");
  expect_refused(dir, "# only a comment\r\n\r\n", 0, "the file has no header row, only comments");
}

TEST(RecordingReader, HeaderWithoutDataRowsIsRefused) {
  TempDir dir;
  expect_refused(dir, "# c\nt_s,i_A,z_mm\n# no data\n\n", 2,
                 "the header is not followed by any data row");
}

TEST(RecordingReader, MissingFileIsNamed) {
  TempDir dir;
  const auto csv = dir / "absent.csv";
  expect_recording_error([&] { read_recording(csv); }, csv, 0,
                         "cannot open: No such file or directory");
}
