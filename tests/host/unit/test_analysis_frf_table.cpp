// SPDX-License-Identifier: Apache-2.0
// Frequency-response tables: both layouts give the same G, the optional sigma column, comments,
// the sign-convention note, and every refusal with its exact text (file:line: problem).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"
#include "test_recording_util.hpp"

namespace {

namespace an = palp::analysis;
using cd = std::complex<double>;

std::string error_of(const std::string& text) {
  try {
    an::parse_frf_table(text, "g.csv");
  } catch (const palp::RecordingError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FrfTable, BothLayoutsGiveTheSameResponse) {
  const cd g[3] = {{0.01, -0.002}, {0.03, -0.04}, {-0.002, -0.0005}};
  std::string re_im = "f_Hz,re_m_per_N,im_m_per_N\n";
  std::string mag_phase = "# from a lock-in\nf_Hz, mag_m_per_N, phase_deg\r\n";
  for (int k = 0; k < 3; ++k) {
    char row[160];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g\n", 2.0 + k, g[k].real(), g[k].imag());
    re_im += row;
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g\r\n", 2.0 + k, std::abs(g[k]),
                  std::arg(g[k]) * 180.0 / std::numbers::pi);
    mag_phase += row;
    if (k == 0) mag_phase += "\n# a comment between rows\n";
  }
  const an::Frf a = an::parse_frf_table(re_im, "a.csv");
  const an::Frf b = an::parse_frf_table(mag_phase, "b.csv");
  ASSERT_EQ(a.lines.size(), 3u);
  ASSERT_EQ(b.lines.size(), 3u);
  EXPECT_EQ(a.method, "table");
  EXPECT_DOUBLE_EQ(a.line_spacing_Hz, 1.0);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(a.lines[k].f_Hz, 2.0 + static_cast<double>(k));
    EXPECT_EQ(b.lines[k].f_Hz, a.lines[k].f_Hz);
    EXPECT_EQ(a.lines[k].G_m_per_N, g[k]);
    EXPECT_NEAR(std::abs(b.lines[k].G_m_per_N - g[k]), 0.0, 1e-15);
    EXPECT_EQ(a.lines[k].sigma_m_per_N, 0.0);
  }
  EXPECT_TRUE(a.notes.empty());
  EXPECT_TRUE(b.notes.empty());
}

TEST(FrfTable, TheSigmaColumnGivesEachLinesNoise) {
  const an::Frf f = an::parse_frf_table(
      "f_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N\n1,1e-3,-1e-4,2e-5\n2,1e-3,-2e-4,3e-5\n"
      "3,1e-3,-3e-4,0\n",
      "s.csv");
  ASSERT_EQ(f.lines.size(), 3u);
  EXPECT_EQ(f.lines[0].sigma_m_per_N, 2e-5);
  EXPECT_EQ(f.lines[1].sigma_m_per_N, 3e-5);
  EXPECT_EQ(f.lines[2].sigma_m_per_N, 0.0);
}

TEST(FrfTable, MostlyPositiveImaginaryPartsGiveTheSignNote) {
  const an::Frf f = an::parse_frf_table(
      "f_Hz,re_m_per_N,im_m_per_N\n1,1e-3,1e-4\n2,1e-3,2e-4\n3,-1e-3,-3e-4\n", "flip.csv");
  ASSERT_EQ(f.notes.size(), 1u);
  EXPECT_EQ(f.notes[0],
            "2 of the 3 Im G values of flip.csv are positive: the table probably uses the opposite "
            "sign convention (a passive system has Im G <= 0 with x = Re{X e^{jwt}}); the data are "
            "used as they are");
  EXPECT_EQ(f.lines[0].G_m_per_N, cd(1e-3, 1e-4));  // used as they are
}

TEST(FrfTable, RefusesABadHeaderNamingTheLayouts) {
  EXPECT_EQ(error_of("# c\nf_Hz,re,im\n1,2,3\n"),
            "g.csv:2: unknown header \"f_Hz,re,im\"; a frequency-response table starts with the "
            "header f_Hz,re_m_per_N,im_m_per_N or f_Hz,mag_m_per_N,phase_deg, optionally followed "
            "by sigma_m_per_N");
  EXPECT_EQ(error_of("# only a comment\n"),
            "g.csv: no header row; a frequency-response table starts with the header "
            "f_Hz,re_m_per_N,im_m_per_N or f_Hz,mag_m_per_N,phase_deg, optionally followed by "
            "sigma_m_per_N");
}

TEST(FrfTable, RefusesBadRowsWithFileLineAndProblem) {
  const std::string h = "f_Hz,re_m_per_N,im_m_per_N\n";
  EXPECT_EQ(error_of(h + "1,1e-3,-1e-4\n2,1e-3\n"), "g.csv:3: 2 cells where the header has 3");
  EXPECT_EQ(error_of(h + "1,1e-3,-1e-4\n2,0,001,-1e-4\n"),
            "g.csv:3: 4 cells where the header has 3 (a decimal comma? numbers need a decimal "
            "point)");
  EXPECT_EQ(error_of(h + "1,1e-3,-1e-4\n2,1e-3,abc\n"),
            "g.csv:3: column im_m_per_N: \"abc\" is not a finite number");
  EXPECT_EQ(error_of(h + "1,nan,-1e-4\n"), "g.csv:2: column re_m_per_N: \"nan\" is not a finite number");
  EXPECT_EQ(error_of(h + "1,1e-3,-1e-4\n2,1e-3,-1e-4\n2,1e-3,-1e-4\n"),
            "g.csv:4: f_Hz 2 does not increase (the row before has 2)");
  EXPECT_EQ(error_of(h + "0,1e-3,-1e-4\n"), "g.csv:2: f_Hz must be positive (got 0)");
  EXPECT_EQ(error_of("f_Hz,mag_m_per_N,phase_deg\n1,-1e-3,-10\n"),
            "g.csv:2: mag_m_per_N must not be negative (got -0.001)");
  EXPECT_EQ(error_of("f_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N\n1,1e-3,-1e-4,-1\n"),
            "g.csv:2: sigma_m_per_N must not be negative (got -1)");
  EXPECT_EQ(error_of(h + "1,1e-3,-1e-4\n2,1e-3,-1e-4\n"),
            "g.csv: the table has 2 rows; a frequency response needs at least 3");
}

TEST(FrfTable, ReadsAFileAndNamesItInErrors) {
  const palp_test::TempDir dir;
  const std::filesystem::path file = dir / "t.csv";
  std::ofstream(file) << "f_Hz,re_m_per_N,im_m_per_N\n1,1,-1\n2,1,-1\n3,1,-1\n";
  EXPECT_EQ(an::read_frf_table(file).lines.size(), 3u);
  try {
    an::read_frf_table(dir / "missing.csv");
    ADD_FAILURE() << "no error";
  } catch (const palp::RecordingError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "missing.csv").string() + ": cannot open: No such file or directory");
    EXPECT_EQ(e.line(), 0u);
  }
}

}  // namespace
