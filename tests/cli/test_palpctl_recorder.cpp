// SPDX-License-Identifier: Apache-2.0
// palpctl stream / run write what the SDK's recorder (palp/recorder.hpp) writes: against one
// real palp-sim, a recording by palpctl and one by palp::record with the same settings have the
// same CSV header and the same sidecar keys, in the same order.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "../host/sim/json_keys.hpp"
#include "cli_process.hpp"
#include "palp/probe.hpp"
#include "palp/recorder.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;

class PalpctlRecorder : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("palpctl-rec-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string out(const std::string& name) const { return (dir_ / name).string(); }

  /// palpctl's recording `cli` and the SDK's `sdk` of the same settings have one structure.
  void expect_same_files(const std::string& cli, const std::string& sdk) {
    EXPECT_EQ(palp::test::first_line(out(cli + ".csv")), palp::test::first_line(out(sdk + ".csv")));
    const auto a = palp::test::read_ordered_json(out(cli + ".json"));
    const auto b = palp::test::read_ordered_json(out(sdk + ".json"));
    EXPECT_EQ(palp::test::key_paths(a), palp::test::key_paths(b)) << a.dump(2) << "\n" << b.dump(2);
  }

  palp::RecordResult record(palp::RecordSettings s) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    palp::Probe probe(sim_.uri());
    return palp::record(probe, std::move(s));
  }

  ProcessResult run(std::vector<std::string> args) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args);
  }

  SimServer sim_;
  fs::path dir_;
};

TEST_F(PalpctlRecorder, StreamWritesTheHeaderAndSidecarKeysOfTheSdkRecorder) {
  const auto r = run({"stream", "--seconds", "0.2", "--zero-current", "--zero-s", "0.05", "--out",
                      out("cli")});
  ASSERT_EQ(r.code, 0) << r.err;
  record({.out = out("sdk"), .duration_s = 0.2, .zero_current = true, .zero_s = 0.05,
          .no_program_reason = "palpctl stream: no program ran"});
  expect_same_files("cli", "sdk");
}

TEST_F(PalpctlRecorder, RunRampWritesTheHeaderAndSidecarKeysOfTheSdkRecorder) {
  const auto r = run({"run", "ramp", "--start-A", "0.1", "--stop-A", "0.3", "--step-A", "0.1",
                      "--dwell-s", "0.05", "--reps", "2", "--out", out("cli")});
  ASSERT_EQ(r.code, 0) << r.err;
  palp::RampProgram m;
  m.start_A = 0.1f;
  m.stop_A = 0.3f;
  m.step_A = 0.1f;
  m.dwell_s = 0.05f;
  m.repetitions = 2;
  const auto rec = record({.out = out("sdk"), .program = m});
  ASSERT_TRUE(rec.program);
  EXPECT_EQ(rec.program->end, palp::proto::ProgramEnd::completed);
  expect_same_files("cli", "sdk");
}

}  // namespace
}  // namespace palpctl::test
