// SPDX-License-Identifier: Apache-2.0
// result.json's "run" block (host/src/experiments/run_json.hpp): one field table per experiment,
// written and read back the same; a missing key named in result.json's way.
#include <gtest/gtest.h>

#include <string>

#include "experiments/run_json.hpp"
#include "palp/error.hpp"

namespace {

using nlohmann::json;

/// The ConfigError text `f` throws ("" when it throws none).
template <class F>
std::string run_block_error(F f) {
  try {
    f();
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "";
}

palp::IndentationRun distinct_indentation_run() {
  palp::IndentationRun run;
  run.program.end = palp::proto::ProgramEnd::stopped_by_host;
  run.program.t_device_s = 12.25;
  run.program.repetitions_done = 3;
  run.samples_missing = (std::uint64_t{1} << 53) + 1;  // beyond a double's integers: read exactly
  run.interrupted = false;
  run.float_z_m = 0.0125;
  return run;
}

TEST(ResultRunJson, IndentationRunBlockHasTheDocumentedKeysAndReadsBackEveryField) {
  const auto run = distinct_indentation_run();
  const json j = palp::indentation_run_json(run);
  EXPECT_EQ(j.dump(),
            R"({"end":"stopped_by_host","float_z_mm":12.5,"interrupted":false,"repetitions_done":3,)"
            R"("samples":0,"samples_missing":9007199254740993,"t_device_s":12.25})");
  palp::IndentationRun back;
  palp::read_indentation_run(j, back);
  EXPECT_EQ(back.program.t_device_s, run.program.t_device_s);
  EXPECT_EQ(back.program.repetitions_done, run.program.repetitions_done);
  EXPECT_EQ(back.samples_missing, run.samples_missing);
  EXPECT_EQ(back.interrupted, run.interrupted);
  EXPECT_EQ(back.float_z_m, run.float_z_m);
}

TEST(ResultRunJson, AnInterruptedRunEndsAsInterruptedAndReadsBackInterrupted) {
  auto run = distinct_indentation_run();
  run.interrupted = true;
  const json j = palp::indentation_run_json(run);
  EXPECT_EQ(j["end"], "interrupted");
  palp::IndentationRun back;
  palp::read_indentation_run(j, back);
  EXPECT_TRUE(back.interrupted);
}

TEST(ResultRunJson, IndentationRunReaderNamesAMissingKeyAndAWrongCount) {
  json j = palp::indentation_run_json(distinct_indentation_run());
  palp::IndentationRun back;
  j.erase("float_z_mm");
  EXPECT_EQ(run_block_error([&] { palp::read_indentation_run(j, back); }), "missing key \"run.float_z_mm\"");
  j = palp::indentation_run_json(distinct_indentation_run());
  j["samples_missing"] = -1;
  EXPECT_EQ(run_block_error([&] { palp::read_indentation_run(j, back); }),
            "\"run.samples_missing\" is not a non-negative integer");
  EXPECT_EQ(run_block_error([&] { palp::read_indentation_run(json::array(), back); }), "\"run\" is not an object");
}

TEST(ResultRunJson, IdentificationRunBlockHasTheDocumentedKeysAndReadsBackEveryField) {
  palp::IdentificationRun run;
  run.program.end = palp::proto::ProgramEnd::completed;
  run.program.t_device_s = 40.5;
  run.samples_missing = 7;
  run.interrupted = false;
  run.control_rate_Hz = 1000;
  const json j = palp::identification_run_json(run);
  EXPECT_EQ(j.dump(),
            R"({"control_rate_Hz":1000,"end":"completed","interrupted":false,"samples":0,)"
            R"("samples_missing":7,"t_device_s":40.5})");
  palp::IdentificationRun back;
  palp::read_identification_run(j, back);
  EXPECT_EQ(back.program.t_device_s, run.program.t_device_s);
  EXPECT_EQ(back.samples_missing, run.samples_missing);
  EXPECT_EQ(back.interrupted, run.interrupted);
  EXPECT_EQ(back.control_rate_Hz, run.control_rate_Hz);

  json missing = j;
  missing.erase("control_rate_Hz");
  EXPECT_EQ(run_block_error([&] { palp::read_identification_run(missing, back); }),
            "missing key \"run.control_rate_Hz\"");
}

}  // namespace
