// SPDX-License-Identifier: Apache-2.0
// Writing and reading back: bit-exact doubles (0.1, 1e-7, -0.0, subnormals, the extremes), a
// million rows, column subsets; the writer's atomicity (nothing under the final names until
// finish(), nothing at all when it is destroyed unfinished) and its refusals.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>

#include "palp/error.hpp"
#include "palp/protocol/crc32.hpp"
#include "palp/recording.hpp"
#include "recording/internal.hpp"
#include "test_recording_util.hpp"

using palp::Column;
using palp::ColumnSet;
using palp::ConfigError;
using palp::Overwrite;
using palp::read_recording;
using palp::Recording;
using palp::RecordingRow;
using palp::RecordingWriter;
using palp::Sidecar;
using palp_test::expect_recording_error;
using palp_test::read_text;
using palp_test::TempDir;
using testing::ElementsAre;
using testing::MatchesRegex;

namespace {

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

std::string hex(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(v));
  return buf;
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b,
                      const char* column) {
  ASSERT_EQ(a.size(), b.size()) << column;
  for (std::size_t k = 0; k < a.size(); ++k)
    ASSERT_EQ(bits(a[k]), bits(b[k])) << column << "[" << k << "]: " << a[k] << " vs " << b[k];
}

void expect_same_recording(const Recording& a, const Recording& b) {
  expect_same_bits(a.t_s, b.t_s, "t_s");
  expect_same_bits(a.i_A, b.i_A, "i_A");
  expect_same_bits(a.z_mm, b.z_mm, "z_mm");
  expect_same_bits(*a.i_cmd_A, *b.i_cmd_A, "i_cmd_A");
  for (std::size_t c = 0; c < 6; ++c) expect_same_bits(*a.p_Pa[c], *b.p_Pa[c], "p_Pa");
  EXPECT_EQ(*a.sample_index, *b.sample_index);
  EXPECT_EQ(*a.status, *b.status);
  EXPECT_EQ(a.rep, b.rep);
}

RecordingRow row_at(std::size_t k) {
  const double t = static_cast<double>(k) / 1000.0;
  RecordingRow r;
  r.sample_index = k;
  r.t_s = t;
  r.i_cmd_A = 0.5 + 0.01 * static_cast<double>(k / 100 % 250);
  r.i_A = r.i_cmd_A + 1e-4 * std::sin(static_cast<double>(k));
  r.z_mm = -3.2 + 0.001 * static_cast<double>(k % 7000);
  for (std::size_t c = 0; c < 6; ++c) r.p_Pa[c] = 100.0 * static_cast<double>(c) + t / 3.0;
  r.status = static_cast<std::uint16_t>(k % 17);
  r.rep = static_cast<int>(k / 25000);
  return r;
}

}  // namespace

TEST(RecordingRoundTrip, AwkwardDoublesReadBackBitExact) {
  TempDir dir;
  const double subnormal = std::numeric_limits<double>::denorm_min();
  const double big = std::numeric_limits<double>::max();
  const std::vector<RecordingRow> rows = {
      {.sample_index = 0,
       .t_s = -0.0,
       .i_cmd_A = 0.1,
       .i_A = -0.0,
       .z_mm = 1e-7,
       .p_Pa = {0.1, 0.2, 0.30000000000000004, 1.0 / 3.0, -1e300, subnormal},
       .status = 0,
       .rep = 0},
      {.sample_index = std::numeric_limits<std::uint64_t>::max(),
       .t_s = 1e-7,
       .i_cmd_A = -big,
       .i_A = big,
       .z_mm = -2.5e-310,
       .p_Pa = {3.141592653589793, 2.718281828459045, 1e22, 5e-324, -0.0, 123456.789},
       .status = 65535,
       .rep = -1},
      {.sample_index = 2,
       .t_s = 1e-7,
       .i_cmd_A = 0.7,
       .i_A = 0.1 + 0.2,
       .z_mm = 1e21,
       .p_Pa = {},
       .status = 1,
       .rep = 2147483647},
  };
  {
    RecordingWriter w(dir / "awkward");
    for (const auto& r : rows) w.append(r);
    w.finish({});
  }
  const std::string text = read_text(dir / "awkward.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "sample_index,t_s,i_cmd_A,i_A,z_mm,p1_Pa,p2_Pa,p3_Pa,p4_Pa,p5_Pa,p6_Pa,status,rep");
  EXPECT_THAT(text, testing::HasSubstr("\n0,-0,0.1,-0,1e-07,0.1,0.2,0.30000000000000004,"
                                       "0.3333333333333333,-1e+300,5e-324,0,0\n"));

  const Recording back = read_recording(dir / "awkward.csv");
  Recording expected;
  for (const auto& r : rows) expected.append(r);
  expect_same_recording(back, expected);
  EXPECT_EQ(back.rep_source, palp::RepSource::column);
}

TEST(RecordingRoundTrip, RewritingAReadRecordingGivesIdenticalFiles) {
  TempDir dir;
  {
    RecordingWriter w(dir / "a");
    for (std::size_t k = 0; k < 500; ++k) w.append(row_at(k));
    Sidecar s;
    s.program = {{"kind", "ramp"}, {"step_A", 0.01}};
    s.stroke_origin_z_mm = -0.0;
    w.finish(s);
  }
  palp::write_recording(dir / "b.csv", read_recording(dir / "a.csv"));
  EXPECT_EQ(read_text(dir / "a.csv"), read_text(dir / "b.csv"));
  EXPECT_EQ(read_text(dir / "a.json"), read_text(dir / "b.json"));
}

TEST(RecordingRoundTrip, MillionRowsAreWrittenAndReadBackBitExact) {
  TempDir dir;
  constexpr std::size_t n = 1'000'000;
  Recording expected;
  {
    RecordingWriter w(dir / "big");
    for (std::size_t k = 0; k < n; ++k) {
      const RecordingRow r = row_at(k);
      w.append(r);
      expected.append(r);
    }
    EXPECT_EQ(w.rows(), n);
    w.finish({});
  }
  const Recording back = read_recording(dir / "big.csv");
  ASSERT_EQ(back.size(), n);
  expect_same_recording(back, expected);
  EXPECT_EQ(back.sidecar->csv_rows, n);
}

TEST(RecordingRoundTrip, ColumnSubsetIsWrittenInOrderAndReadAsAbsent) {
  TempDir dir;
  const ColumnSet columns = ColumnSet::required().with(Column::rep).with(Column::p3_Pa);
  {
    RecordingWriter w(dir / "few.csv", {.columns = columns});
    w.append({.t_s = 0, .i_A = 0.5, .z_mm = 1, .p_Pa = {1, 2, 3, 4, 5, 6}, .rep = 0});
    w.append({.t_s = 0.5, .i_A = 0.75, .z_mm = 2, .p_Pa = {0, 0, 33, 0, 0, 0}, .rep = 1});
    w.finish({});
  }
  EXPECT_EQ(read_text(dir / "few.csv"), "t_s,i_A,z_mm,p3_Pa,rep\n0,0.5,1,3,0\n0.5,0.75,2,33,1\n");
  const Recording r = read_recording(dir / "few.csv");
  EXPECT_EQ(r.columns(), columns);
  EXPECT_FALSE(r.sample_index);
  EXPECT_FALSE(r.status);
  EXPECT_EQ(*r.p_Pa[2], (std::vector<double>{3, 33}));
  EXPECT_EQ(r.rep, (std::vector<int>{0, 1}));
}

TEST(RecordingWriter, NothingAppearsUnderTheFinalNamesUntilFinish) {
  TempDir dir;
  RecordingWriter w(dir / "run");
  EXPECT_EQ(w.csv_path(), dir / "run.csv");
  EXPECT_EQ(w.sidecar_path(), dir / "run.json");
  for (std::size_t k = 0; k < 100; ++k) w.append(row_at(k));
  const auto during = dir.files();
  ASSERT_EQ(during.size(), 1u);
  EXPECT_THAT(during[0], MatchesRegex("\\.run\\.csv\\.tmp-[0-9]+-[0-9]+"));
  w.finish({});
  EXPECT_TRUE(w.finished());
  EXPECT_THAT(dir.files(), ElementsAre("run.csv", "run.json"));
}

TEST(RecordingWriter, DestroyedWithoutFinishLeavesNoFileAtAll) {
  TempDir dir;
  {
    RecordingWriter w(dir / "crashed");
    for (std::size_t k = 0; k < 300'000; ++k) w.append(row_at(k));  // some of it on the disk
  }
  EXPECT_THAT(dir.files(), ElementsAre());
  {
    RecordingWriter moved_from(dir / "moved");
    RecordingWriter w = std::move(moved_from);
    w.append(row_at(0));
  }
  EXPECT_THAT(dir.files(), ElementsAre());
}

TEST(RecordingWriter, RefusesToOverwriteUnlessAsked) {
  TempDir dir;
  palp_test::write_text(dir / "run.json", "{}");
  try {
    RecordingWriter w(dir / "run");
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "run.json").string() +
                                         " already exists; choose another name, or pass "
                                         "WriterOptions{.overwrite = palp::Overwrite::yes} to "
                                         "replace it");
  }
  RecordingWriter w(dir / "run", {.overwrite = Overwrite::yes});
  w.append(row_at(0));
  w.finish({});
  EXPECT_EQ(read_recording(dir / "run.csv").size(), 1u);
}

TEST(RecordingWriter, RefusesNonFiniteValuesAndDecreasingTimeAndStaysUsable) {
  TempDir dir;
  RecordingWriter w(dir / "run");
  const std::string name = (dir / "run.csv").string();
  w.append({.t_s = 1.5, .i_A = 1});
  RecordingRow nan_row{.t_s = 2, .i_A = 1};
  nan_row.p_Pa[4] = std::nan("");
  try {
    w.append(nan_row);
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              name + ": row 1: p5_Pa is nan; a recording holds finite numbers only");
  }
  try {
    w.append({.t_s = 1.25, .i_A = 1});
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              name + ": row 1: t_s 1.25 is below the previous row's 1.5; t_s must not decrease");
  }
  w.append({.t_s = 1.5, .i_A = 2});
  w.finish({});
  EXPECT_EQ(read_recording(dir / "run.csv").i_A, (std::vector<double>{1, 2}));
  EXPECT_THROW(w.append({.t_s = 3}), ConfigError);
  EXPECT_THROW(w.finish({}), ConfigError);
}

TEST(RecordingWriter, FinishWithoutRowsIsRefused) {
  TempDir dir;
  RecordingWriter w(dir / "run");
  try {
    w.finish({});
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "run.csv").string() + ": no row was appended; a recording needs at least one");
  }
}

TEST(RecordingWriter, PathsGetTheirExtensions) {
  EXPECT_EQ(palp::recording_csv_path("data/run"), "data/run.csv");
  EXPECT_EQ(palp::recording_csv_path("data/run.csv"), "data/run.csv");
  EXPECT_EQ(palp::recording_csv_path("data/run.v2"), "data/run.v2.csv");
  EXPECT_EQ(palp::recording_sidecar_path("data/run.csv"), "data/run.json");
  EXPECT_EQ(palp::recording_sidecar_path("data/run.v2.csv"), "data/run.v2.json");
}

// A crash between the two renames while overwriting leaves the new sidecar beside the old CSV:
// the reader refuses the pair.
TEST(RecordingWriter, SidecarOfAnotherWriteIsRefused) {
  TempDir dir;
  const auto write = [&](const std::string& stem, std::size_t rows, double offset) {
    RecordingWriter w(dir / stem);
    for (std::size_t k = 0; k < rows; ++k) {
      RecordingRow r = row_at(k);
      r.z_mm += offset;
      w.append(r);
    }
    w.finish({});
  };
  write("old", 2, 0);
  write("new", 3, 0);
  write("same_length", 2, 1000);  // same rows, other numbers
  const std::string why =
      ": the two files are not from one write (a CSV edited by hand, or an overwrite that was "
      "interrupted); to load them anyway, read with "
      "ReadOptions{.check_sidecar_matches_csv = false}";
  std::filesystem::copy_file(dir / "new.json", dir / "old.json",
                             std::filesystem::copy_options::overwrite_existing);
  expect_recording_error([&] { read_recording(dir / "old.csv"); }, dir / "old.json", 0,
                         "\"csv_rows\" is 3, but old.csv has 2 data rows" + why);

  std::filesystem::copy_file(dir / "same_length.json", dir / "old.json",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string old_csv = read_text(dir / "old.csv");
  const auto old_crc =
      palp::proto::crc32(reinterpret_cast<const std::uint8_t*>(old_csv.data()), old_csv.size());
  const auto claimed_crc = *palp::read_sidecar(dir / "same_length.json").csv_crc32;
  ASSERT_NE(old_crc, claimed_crc);
  expect_recording_error(
      [&] { read_recording(dir / "old.csv"); }, dir / "old.json", 0,
      "\"csv_crc32\" is " + hex(claimed_crc) + ", but old.csv's CRC-32 is " + hex(old_crc) + why);

  EXPECT_EQ(read_recording(dir / "old.csv", {.check_sidecar_matches_csv = false}).size(), 2u);
  EXPECT_FALSE(read_recording(dir / "old.csv", {.read_sidecar = false}).sidecar.has_value());
}

// The CSV's CRC-32, eight bytes at a time, is the protocol's (zlib's) CRC for every length and
// alignment, and in pieces of any size.
TEST(RecordingRoundTrip, Crc32EightBytesAtATimeIsTheProtocolsCrc) {
  using palp::recording_detail::Crc32;
  EXPECT_EQ(Crc32::final(Crc32::update(Crc32::kInit, "123456789", 9)), 0xCBF43926u);
  std::string bytes;
  for (int k = 0; k < 300; ++k) bytes += static_cast<char>((k * 7919) & 0xFF);
  for (std::size_t offset = 0; offset < 8; ++offset)
    for (std::size_t size = 0; offset + size <= bytes.size(); size += 13) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data() + offset);
      const std::uint32_t whole =
          Crc32::final(Crc32::update(Crc32::kInit, bytes.data() + offset, size));
      ASSERT_EQ(whole, palp::proto::crc32(p, size)) << offset << " " << size;
      const std::size_t half = size / 3;
      const std::uint32_t pieces =
          Crc32::final(Crc32::update(Crc32::update(Crc32::kInit, bytes.data() + offset, half),
                                     bytes.data() + offset + half, size - half));
      ASSERT_EQ(pieces, whole);
    }
}
