// SPDX-License-Identifier: Apache-2.0
// palpctl's device commands against a real palp-sim (one per test; palp-sim serves one device
// client at a time, so every palpctl run waits until it has seen the previous one go).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class PalpctlDevice : public SimCliTest {
 protected:
  PalpctlDevice() : SimCliTest("palpctl") {}
  std::string out(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(PalpctlDevice, InfoJsonNamesTheDeviceAndItsSettingsInLabUnits) {
  const auto r = run({"info", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["device"]["serial"], "SIM-0001");
  EXPECT_EQ(j["device"]["board"], "palp-sim");
  EXPECT_EQ(j["handshake"]["verdict"], "compatible");
  EXPECT_DOUBLE_EQ(j["params"]["current_clamp_A"].get<double>(), 3.2);
  EXPECT_DOUBLE_EQ(j["params"]["travel_max_mm"].get<double>(), 35.0);     // 35000 counts
  EXPECT_DOUBLE_EQ(j["calibration"]["spring_k_N_per_mm"].get<double>(), 0.0439);  // 43.9 N/m
  EXPECT_TRUE(j["calibration"]["stroke_origin_mm"].is_null());
  EXPECT_TRUE(j["calibration"].contains("stroke_origin_mm_reason"));
  EXPECT_TRUE(j["health"]["device"].is_object());
  EXPECT_EQ(j["status"]["state"], "idle");
}

TEST_F(PalpctlDevice, RunHoldWritesARecordingThatReadsBack) {
  const auto r = run({"--json", "run", "hold", "--current-A", "0.5", "--seconds", "0.2",
                      "--rate-Hz", "1000", "--out", out("run.csv")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "no progress with --json: " << r.err;
  const json summary = json::parse(r.out);
  EXPECT_EQ(summary["program"]["result"]["end"], "completed");

  ASSERT_TRUE(fs::exists(out("run.csv")));
  ASSERT_TRUE(fs::exists(out("run.json")));
  const palp::Recording rec = palp::read_recording(out("run.csv"));
  EXPECT_EQ(summary["samples"].get<std::size_t>(), rec.size());
  EXPECT_GE(rec.size(), 200u);
  ASSERT_TRUE(rec.i_cmd_A);
  EXPECT_EQ(std::count(rec.i_cmd_A->begin(), rec.i_cmd_A->end(), 0.5), 200)
      << "0.2 s at 0.5 A, 1000 samples per second";
  ASSERT_TRUE(rec.sidecar);
  const auto& side = *rec.sidecar;
  EXPECT_EQ(side.program["kind"], "hold");
  EXPECT_DOUBLE_EQ(side.program["parameters"]["current_A"].get<double>(), 0.5);
  EXPECT_EQ(side.device["serial"], "SIM-0001");
  EXPECT_TRUE(side.calibration.is_object());
  EXPECT_FALSE(side.stroke_origin_z_mm) << "the simulator starts un-homed";
  EXPECT_TRUE(side.zeroing.empty());
  EXPECT_EQ(side.extra["samples_missing"], 0);
}

TEST_F(PalpctlDevice, RunRampRecordsRepetitionsAndTheZeroingInTheSidecar) {
  // 0.5 -> 1.0 A by 0.1 A, 20 ms a step, unload: 11 stairs = 0.22 s a repetition
  const auto r = run({"run", "ramp", "--start-A", "0.5", "--stop-A", "1", "--step-A", "0.1",
                      "--dwell-s", "0.02", "--reps", "2", "--rate-Hz", "1000",
                      "--zero-pressure", "--out", out("ramp.csv")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("%"), std::string::npos) << "progress on stderr: " << r.err;

  const palp::Recording rec = palp::read_recording(out("ramp.csv"));
  ASSERT_GE(rec.size(), 440u);
  EXPECT_EQ(*std::max_element(rec.i_cmd_A->begin(), rec.i_cmd_A->end()), 1.0);
  // repetition 0, then 1 from the 221st program sample on, never back
  EXPECT_EQ(rec.rep.front(), 0);
  EXPECT_EQ(rec.rep.back(), 1);
  EXPECT_TRUE(std::is_sorted(rec.rep.begin(), rec.rep.end()));
  const auto first_running = std::find_if(rec.i_cmd_A->begin(), rec.i_cmd_A->end(),
                                          [](double i) { return i != 0.0; }) -
                             rec.i_cmd_A->begin();
  const auto first_rep1 = std::find(rec.rep.begin(), rec.rep.end(), 1) - rec.rep.begin();
  EXPECT_EQ(first_rep1 - first_running, 220);

  const auto& side = *rec.sidecar;
  EXPECT_EQ(side.program["parameters"]["reps"], 2);
  EXPECT_EQ(side.program["result"]["repetitions_done"], 2);
  ASSERT_EQ(side.zeroing.size(), 1u);
  EXPECT_EQ(side.zeroing[0]["what"], "pressure_zero");
  EXPECT_EQ(side.zeroing[0]["values_unit"], "Pa");
  EXPECT_EQ(side.zeroing[0]["values"].size(), 6u);
  EXPECT_EQ(side.zeroing[0]["committed"], false) << "zeroing before a run stays in RAM";
}

TEST_F(PalpctlDevice, AnExistingRecordingIsReplacedOnlyWithOverwrite) {
  const std::vector<std::string> hold = {"run", "hold", "--current-A", "0.2", "--seconds", "0.05",
                                         "--out", out("h.csv")};
  ASSERT_EQ(run(hold).code, 0);
  const auto again = run(hold);
  EXPECT_EQ(again.code, 2) << again.err;
  EXPECT_NE(again.err.find("--overwrite"), std::string::npos) << again.err;
  auto replace = hold;
  replace.push_back("--overwrite");
  EXPECT_EQ(run(replace).code, 0);
}

TEST_F(PalpctlDevice, StreamRecordsExactlyTheSecondsAsked) {
  const auto r = run({"stream", "--seconds", "0.3", "--rate-Hz", "2000", "--out", out("s")});
  ASSERT_EQ(r.code, 0) << r.err;
  const palp::Recording rec = palp::read_recording(out("s.csv"));
  EXPECT_EQ(rec.size(), 600u);
  EXPECT_EQ(rec.sample_index->front(), 0u);
  EXPECT_EQ(rec.sample_index->back(), 599u);
  EXPECT_TRUE(rec.sidecar->program.is_null());
  EXPECT_DOUBLE_EQ(rec.sidecar->extra["stream"]["rate_Hz"].get<double>(), 2000.0);
}

TEST_F(PalpctlDevice, CalibrateCommitsUnlessRamOnly) {
  const auto ram = run({"--json", "calibrate", "current-offset", "--ram-only", "--seconds", "0.1"});
  ASSERT_EQ(ram.code, 0) << ram.err;
  const json j = json::parse(ram.out);
  EXPECT_EQ(j["committed"], false);
  EXPECT_TRUE(j["current_offset_A"].is_number());
  EXPECT_DOUBLE_EQ(j["calibration"]["current_offset_A"].get<double>(),
                   j["current_offset_A"].get<double>());

  const auto home = run({"--json", "calibrate", "home", "--current-A", "-0.3", "--seconds", "0.5"});
  ASSERT_EQ(home.code, 0) << home.err;
  const json h = json::parse(home.out);
  EXPECT_EQ(h["committed"], true);
  EXPECT_EQ(h["calibration"]["stroke_origin_valid"], true);
  EXPECT_DOUBLE_EQ(h["calibration"]["stroke_origin_mm"].get<double>(),
                   h["stroke_origin_mm"].get<double>());
}

TEST_F(PalpctlDevice, FaultClearOnAHealthyDeviceExits0) {
  const auto r = run({"--json", "fault", "clear"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["cleared"], true);
  EXPECT_EQ(j["after"]["reason"], "none");
}

TEST_F(PalpctlDevice, AFaultDuringARunExits6KeepsTheRecordingAndClearsOnceItsCauseIsGone) {
  {  // a 1 mm travel window about the resting coil (set over the SDK, then the link is closed)
    palp::Probe probe(sim_.uri());
    auto p = probe.params();
    const std::int32_t c = probe.status().encoder_counts;
    p.travel_min_counts = c - 500;
    p.travel_max_counts = c + 500;
    probe.set_params(p);
  }
  const auto r = run({"run", "hold", "--current-A", "1", "--seconds", "2", "--out", out("f.csv")});
  EXPECT_EQ(r.code, 6) << r.err;
  EXPECT_NE(r.err.find("travel_limit"), std::string::npos) << r.err;
  const palp::Recording rec = palp::read_recording(out("f.csv"));  // kept, and complete
  EXPECT_GT(rec.size(), 0u);
  EXPECT_EQ(rec.sidecar->program["fault"]["reason"], "travel_limit");
  EXPECT_TRUE(rec.sidecar->program["result"].is_null());

  const auto refused = run({"run", "hold", "--current-A", "0.2", "--seconds", "0.1", "--out",
                            out("g.csv")});
  EXPECT_EQ(refused.code, 6) << "the latch refuses programs: " << refused.err;
  EXPECT_FALSE(fs::exists(out("g.csv")));

  const auto shown = run({"--json", "fault", "show"});
  ASSERT_EQ(shown.code, 0) << shown.err;
  EXPECT_EQ(json::parse(shown.out)["fault"]["reason"], "travel_limit");

  // with the current off the springs bring the coil back into the window; until then the
  // device refuses the clear (exit 6)
  int code = -1;
  for (int attempt = 0; attempt < 50 && code != 0; ++attempt) {
    code = run({"fault", "clear"}).code;
    EXPECT_TRUE(code == 0 || code == 6) << code;
    if (code != 0) ::usleep(50000);
  }
  EXPECT_EQ(code, 0);
}

TEST_F(PalpctlDevice, MonitorPrintsLiveValuesUntilSeconds) {
  const auto r = run({"--json", "monitor", "--seconds", "0.5", "--interval-s", "0.1"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) {
    const json j = json::parse(line);
    EXPECT_EQ(j["state"], "idle");
    EXPECT_TRUE(j.contains("i_A") && j.contains("z_mm") && j.contains("p_Pa")) << line;
    ++lines;
  }
  EXPECT_GE(lines, 3);
}

}  // namespace
}  // namespace palpctl::test
