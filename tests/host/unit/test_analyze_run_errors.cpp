// SPDX-License-Identifier: Apache-2.0
// The experiments' two kinds of analysis failure (issue 16), for palp::analyze_run and
// palp::analyze_identification: data the analysis cannot use becomes the run's analysis_reason
// (the DataError's exact text), while a bad setting is a ConfigError that reaches the caller
// instead of hiding in a reason.
#include <gtest/gtest.h>

#include <limits>

#include "palp/error.hpp"
#include "palp/indent.hpp"
#include "palp/identification.hpp"

namespace {

/// A run whose recording holds `n` loading samples at or above I_c = 0.5 A (one repetition).
palp::IndentationRun run_with_contact_samples(int n) {
  palp::IndentationRun run;
  run.settings = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
  for (int k = 0; k < n; ++k) {
    palp::RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(k);
    row.t_s = 0.01 * k;
    row.i_cmd_A = row.i_A = 0.5 + 0.01 * k;
    row.z_mm = 25.0 + 0.02 * k;
    run.recording.append(row);
  }
  return run;
}

}  // namespace

TEST(AnalyzeRun, TooFewContactSamplesGiveTheDataErrorsTextAsTheReason) {
  palp::IndentationRun run = run_with_contact_samples(5);
  palp::analyze_run(run);
  EXPECT_FALSE(run.analysis);
  EXPECT_FALSE(run.repetitions);
  EXPECT_EQ(run.analysis_reason,
            "too few points: 5 loading samples at or above I_c = 0.5 A, the fits need at least 10");
  EXPECT_EQ(run.pressure_reason, "no indentation analysis: " + run.analysis_reason);
}

TEST(AnalyzeRun, ABadAnalysisSettingPropagatesAsAConfigError) {
  palp::IndentationRun run = run_with_contact_samples(40);
  run.settings.analysis.poisson = 1.0;  // E* = E / (1 - nu^2) has no value
  EXPECT_THROW(palp::analyze_run(run), palp::ConfigError);
  run.settings.analysis.poisson = 0.5;
  run.settings.analysis.min_points = 2;  // below the 3 a fit needs
  EXPECT_THROW(palp::analyze_run(run), palp::ConfigError);
}

TEST(AnalyzeRun, ANonFiniteSampleIsADataProblemNamedInTheReason) {
  palp::IndentationRun run = run_with_contact_samples(40);
  run.recording.z_mm[7] = std::numeric_limits<double>::quiet_NaN();
  palp::analyze_run(run);
  EXPECT_FALSE(run.analysis);
  EXPECT_EQ(run.analysis_reason.rfind("indentation curve: sample 7 is not finite", 0), 0u) << run.analysis_reason;
}

namespace {

/// A stepped-sine identification run whose recording holds two samples (the program unseen).
palp::IdentificationRun two_sample_identification() {
  palp::IdentificationRun run;
  run.settings.method = palp::SweepMethod::stepped;
  run.sweep = run.settings.sweep_program();
  run.control_rate_Hz = 20000;
  for (int k = 0; k < 2; ++k) {
    palp::RecordingRow row;
    row.t_s = 0.001 * k;
    row.i_cmd_A = row.i_A = 0.5;
    row.z_mm = 25.0;
    run.recording.append(row);
  }
  return run;
}

}  // namespace

TEST(AnalyzeIdentification, ARecordingWithoutTheProgramGivesTheDataErrorsTextAsTheReason) {
  palp::IdentificationRun run = two_sample_identification();
  palp::analyze_identification(run);
  EXPECT_FALSE(run.frf);
  EXPECT_EQ(run.analysis_reason,
            "no frequency response: stepped_sine_frf: the commanded current (i_cmd_A) never "
            "changes: the recording does not show the program");
}

TEST(AnalyzeIdentification, AControlRateTheDeviceDoesNotRunPropagatesAsAConfigError) {
  palp::IdentificationRun run = two_sample_identification();
  run.control_rate_Hz = 12345;
  EXPECT_THROW(palp::analyze_identification(run), palp::ConfigError);
}
