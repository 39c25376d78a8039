// SPDX-License-Identifier: Apache-2.0
// The pressure–force test of a recording (palp/pressure_analysis.hpp) on a synthetic staircase
// whose channel m reads 20 m Pa per newton of object force (test_result_synth.hpp): the slopes,
// the channel numbers of a recording with some channels only, and indent()'s run.pressure being
// this very analysis.
#include <gtest/gtest.h>

#include "palp/error.hpp"
#include "palp/pressure_analysis.hpp"
#include "palp/result.hpp"
#include "test_result_synth.hpp"

namespace {

TEST(PressureAnalysisOf, ARecordingGivesEachChannelsKnownSlopeAndEqualsIndentsRunPressure) {
  const palp::IndentationRun run = palp_test::synthetic_run();
  ASSERT_TRUE(run.pressure.has_value()) << run.pressure_reason;
  const auto pr = palp::pressure_analysis_of(run.recording, run.settings.analysis);
  ASSERT_EQ(pr.channels.size(), 6u);
  for (std::size_t m = 0; m < 6; ++m) {
    EXPECT_EQ(pr.channels[m].channel, static_cast<int>(m) + 1);
    ASSERT_TRUE(pr.channels[m].fit.slope);
    EXPECT_NEAR(*pr.channels[m].fit.slope.value, 20.0 * static_cast<double>(m + 1), 0.05) << m;
  }
  // analyze_run (what indent() calls) gives the same numbers, key for key
  EXPECT_EQ(palp::pressure_summary_json(pr), palp::pressure_summary_json(*run.pressure));
}

TEST(PressureAnalysisOf, OnlyP2AndP5RecordedGiveChannels2And5WithTheirSlopes) {
  palp::IndentationRun run = palp_test::synthetic_run();
  for (std::size_t ch : {0u, 2u, 3u, 5u}) run.recording.p_Pa[ch].reset();
  const auto pr = palp::pressure_analysis_of(run.recording, run.settings.analysis);
  ASSERT_EQ(pr.channels.size(), 2u);
  EXPECT_EQ(pr.channels[0].channel, 2);
  EXPECT_EQ(pr.channels[1].channel, 5);
  EXPECT_NEAR(*pr.channels[0].fit.slope.value, 40.0, 0.05);
  EXPECT_NEAR(*pr.channels[1].fit.slope.value, 100.0, 0.05);
  // and indent()'s analysis of that recording says the same (it used to want all six)
  palp::analyze_run(run);
  ASSERT_TRUE(run.pressure.has_value()) << run.pressure_reason;
  EXPECT_EQ(palp::pressure_summary_json(*run.pressure), palp::pressure_summary_json(pr));
}

TEST(PressureAnalysisOf, ARecordingWithoutPressureColumnsIsADataErrorSayingSo) {
  palp::IndentationRun run = palp_test::synthetic_run();
  for (auto& col : run.recording.p_Pa) col.reset();
  try {
    palp::pressure_analysis_of(run.recording, run.settings.analysis);
    FAIL() << "no DataError";
  } catch (const palp::DataError& e) {
    EXPECT_STREQ(e.what(), "the recording has no pressure column (p1_Pa .. p6_Pa)");
  }
  palp::analyze_run(run);
  EXPECT_FALSE(run.pressure.has_value());
  EXPECT_EQ(run.pressure_reason, "the recording has no pressure column (p1_Pa .. p6_Pa)");
  EXPECT_TRUE(run.analysis.has_value());  // the indentation analysis stands on its own
}

}  // namespace
