// SPDX-License-Identifier: Apache-2.0
// The readers' limits (format/text_input.hpp, docs/reliability.md §4): a line over 64 KiB and a
// file over its kind's limit are refused as soon as the limit is passed, naming the file, the
// line and the limit; what a message quotes of a file is cut at 60 bytes and escaped, so a
// hostile file can neither flood nor drive the terminal. Large files are sparse (all NUL bytes,
// no disk written), which also makes the NUL escaping visible.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "format/text_input.hpp"
#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"
#include "palp/recording.hpp"
#include "palp/result.hpp"
#include "palp/trace.hpp"
#include "palp/rig.hpp"
#include "test_recording_util.hpp"

namespace fs = std::filesystem;
using palp_test::expect_recording_error;
using palp_test::TempDir;
using palp_test::write_text;

namespace {

/// Sixty NUL bytes escaped, then the ellipsis: how a quote of a sparse file reads.
std::string sixty_nuls() {
  std::string s;
  for (int k = 0; k < 60; ++k) s += "\\x00";
  return s + "\u2026";
}

std::string config_error_of(const fs::path& rig) {
  try {
    palp::load_rig(rig);
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(TextQuote, CutsAtSixtyBytesAndEscapesEveryByteOutsidePrintableAscii) {
  EXPECT_EQ(palp::format::quoted("ab\x1b[2J\r\n\x7f\xc2\xb5"), "\"ab\\x1b[2J\\x0d\\x0a\\x7f\\xc2\\xb5\"");
  EXPECT_EQ(palp::format::quoted(std::string(60, 'x')), "\"" + std::string(60, 'x') + "\"");
  EXPECT_EQ(palp::format::quoted(std::string(61, 'x')), "\"" + std::string(60, 'x') + "\u2026\"");
}

TEST(BoundedReaders, RecordingWithAHundredMegabyteLineFailsOnItsFirst64KiBWithACutEscapedQuote) {
  TempDir dir;
  const auto csv = dir / "big.csv";
  {
    std::ofstream out(csv, std::ios::binary);
    out << "t_s,i_A,z_mm\n\x1b]0;pwned\x07";  // a terminal title escape, then 100 MB of 'A'
  }
  fs::resize_file(csv, fs::file_size(csv) + 100'000'000);  // NUL bytes, sparse
  expect_recording_error([&] { palp::read_recording(csv); }, csv, 2,
                         "the line is longer than the limit of 65536 bytes (64 KiB) (it starts "
                         "\"\\x1b]0;pwned\\x07" +
                             std::string(sixty_nuls().substr(4 * 10)) + "\")");
}

TEST(BoundedReaders, RecordingLineOf64KiBWithItsNewlineIsReadOneByteMoreIsRefused) {
  TempDir dir;
  const auto csv = dir / "edge.csv";
  const std::string comment = "#" + std::string(palp::format::kMaxLineBytes - 2, 'c');
  write_text(csv, comment + "\nt_s,i_A,z_mm\n0,1,2\n");  // 65535 bytes + "\n"
  EXPECT_EQ(palp::read_recording(csv).size(), 1u);
  EXPECT_EQ(palp::recording_row_lines(csv), std::vector<std::size_t>{3});
  write_text(csv, comment + "c\nt_s,i_A,z_mm\n0,1,2\n");
  expect_recording_error([&] { palp::read_recording(csv); }, csv, 1,
                         "the line is longer than the limit of 65536 bytes (64 KiB) (it starts \"#" +
                             std::string(59, 'c') + "\u2026\")");
  // the last line, without a newline, has the same limit
  write_text(csv, "t_s,i_A,z_mm\n0,1,2\n" + comment + "cc");
  expect_recording_error([&] { palp::recording_row_lines(csv); }, csv, 3,
                         "the line is longer than the limit of 65536 bytes (64 KiB) (it starts \"#" +
                             std::string(59, 'c') + "\u2026\")");
}

TEST(BoundedReaders, RecordingCellAndHeaderQuotesAreCutAndEscaped) {
  TempDir dir;
  const auto csv = dir / "run.csv";
  write_text(csv, "t_s,i_A,z_mm\n0,\x1b[31m" + std::string(100, '9') + "x,0\n");
  expect_recording_error([&] { palp::read_recording(csv); }, csv, 2,
                         "column i_A: \"\\x1b[31m" + std::string(55, '9') +
                             "\u2026\" is not a number");
}

TEST(BoundedReaders, FrfTableLargerThan16MiBIsRefusedBeforeReadingIt) {
  TempDir dir;
  const auto csv = dir / "table.csv";
  write_text(csv, "f_Hz,re_m_per_N,im_m_per_N\n");
  fs::resize_file(csv, palp::format::kMaxTableFileBytes + 1);
  expect_recording_error([&] { palp::analysis::read_frf_table(csv); }, csv, 0,
                         "the file has 16777217 bytes, more than the limit of 16777216 bytes "
                         "(16 MiB)");
  EXPECT_TRUE(palp::analysis::is_frf_table(csv));  // reads its first line only
}

TEST(BoundedReaders, FrfTableLineLongerThan64KiBIsRefusedWithItsLineNumber) {
  const std::string text = "f_Hz,re_m_per_N,im_m_per_N\n1,1,-1\n" + std::string(70'000, '\0');
  try {
    palp::analysis::parse_frf_table(text, "t.csv");
    ADD_FAILURE() << "no error";
  } catch (const palp::RecordingError& e) {
    EXPECT_EQ(std::string(e.what()),
              "t.csv:3: the line is longer than the limit of 65536 bytes (64 KiB) (it starts \"" +
                  sixty_nuls() + "\")");
  }
}

TEST(BoundedReaders, FrfTableDetectionOfAFileWithoutNewlineReadsOneLineOnly) {
  TempDir dir;
  const auto f = dir / "x.csv";
  write_text(f, "f_Hz");
  fs::resize_file(f, 1'000'000'000);  // sparse
  EXPECT_TRUE(palp::analysis::is_frf_table(f));
  write_text(f, "# comment\r\n\n  t_s,i_A,z_mm\n");
  EXPECT_FALSE(palp::analysis::is_frf_table(f));
}

TEST(BoundedReaders, JsonFilesLargerThan64MiBAreRefusedNamingFileAndLimit) {
  TempDir dir;
  const auto rig = dir / "rig.json";
  write_text(rig, "{");
  fs::resize_file(rig, palp::format::kMaxJsonFileBytes + 1);
  EXPECT_EQ(config_error_of(rig), rig.string() +
                                      ": the file has 67108865 bytes, more than the limit of "
                                      "67108864 bytes (64 MiB)");
  const auto sidecar = dir / "run.json";
  fs::copy_file(rig, sidecar);
  expect_recording_error([&] { palp::read_sidecar(sidecar); }, sidecar, 0,
                         "the file has 67108865 bytes, more than the limit of 67108864 bytes "
                         "(64 MiB)");
}

TEST(BoundedReaders, JsonErrorsQuoteAtMost240BytesOfTheFileEscaped) {
  TempDir dir;
  const auto sidecar = dir / "run.json";
  write_text(sidecar, "{\"schema\": \"" + std::string(1'000'000, 'x') + "\x01\"}");
  try {
    palp::read_sidecar(sidecar);
    ADD_FAILURE() << "no error";
  } catch (const palp::RecordingError& e) {
    const std::string problem = e.problem();
    EXPECT_LT(problem.size(), 320u) << problem.substr(0, 400);
    EXPECT_TRUE(problem.ends_with("\u2026")) << problem.substr(0, 400);
    for (const char c : problem) EXPECT_GE(static_cast<unsigned char>(c), 0x20);
  }
  const auto rig = dir / "rig.json";
  write_text(rig, R"({"a\u001b[2Jb\u00b5": 1})");  // an escape sequence and a µ in a key
  EXPECT_EQ(config_error_of(rig), rig.string() + ": a\\x1b[2Jb\\xc2\\xb5: unknown key");
}

// Found by fuzz_sidecar_json: nlohmann throws out_of_range, not parse_error, for a number beyond
// a double, and the readers caught only parse_error (the exception left palpctl unexplained).
TEST(JsonReaders, ANumberBeyondADoubleIsAJsonErrorNamingTheFile) {
  TempDir dir;
  const std::string overflow = "[json.exception.out_of_range.406] number overflow parsing '1e999'";
  const auto sidecar = dir / "run.json";
  write_text(sidecar, "{\"schema\": 1e999}");
  expect_recording_error([&] { palp::read_sidecar(sidecar); }, sidecar, 0,
                         "not valid JSON: " + overflow);
  try {
    palp::parse_rig("{\"format_version\": 1e999}", "rig.json");
    ADD_FAILURE() << "no error";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "rig.json: JSON error: " + overflow);
  }
  fs::copy_file(sidecar, dir / "trace.json");
  try {
    palp::load_trace(dir / "trace.json");
    ADD_FAILURE() << "no error";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "trace.json").string() + ": not JSON (" + overflow + ")");
  }
  fs::copy_file(sidecar, dir / "result.json");
  expect_recording_error([&] { palp::load_result(dir.path()); }, dir / "result.json", 0,
                         "invalid JSON: " + overflow);
}

// Found by fuzz_sidecar_json: the sidecar reader quoted a wrong value with json::dump, which
// leaves DEL and every non-ASCII character (C1 controls included) as they are.
TEST(JsonReaders, ASidecarsWrongValueIsQuotedEscaped) {
  TempDir dir;
  const auto sidecar = dir / "run.json";
  write_text(sidecar, R"("\u007fab\u0085")");
  expect_recording_error([&] { palp::read_sidecar(sidecar); }, sidecar, 0,
                         "the sidecar must be a JSON object, not a string (\"\\x7fab\\xc2\\x85\")");
}
