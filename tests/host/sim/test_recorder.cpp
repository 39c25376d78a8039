// SPDX-License-Identifier: Apache-2.0
// palp::record / palp::Recorder (palp/recorder.hpp) against palp-sim linked in (virtual time): a
// stream of exactly its duration with health in the sidecar, frames the simulator drops as gap
// records, a cancel that stops program and stream and leaves a complete recording, an error
// mid-run (the stream goes silent) that stops everything and keeps the recording with the error,
// an existing recording refused before a device is used, and docs/recording-format.md's
// example sidecar holding exactly the keys, in order, of one the recorder writes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "json_keys.hpp"
#include "lossy_link.hpp"
#include "palp/recorder.hpp"
#include "palp/recording.hpp"
#include "palp/sim_inproc.hpp"

namespace {

namespace fs = std::filesystem;
using palp::sim::InprocSimulator;
using nlohmann::json;
using namespace std::chrono_literals;

class Recorder : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("palp-recorder-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path out(const std::string& name) const { return dir_ / name; }

  fs::path dir_;
};

/// A ramp that takes `reps` x 1.9 s of device time (0.1 -> 1 A by 0.1 A, 0.1 s a step, unload).
palp::RampProgram ramp(int reps) {
  palp::RampProgram m;
  m.start_A = 0.1f;
  m.stop_A = 1.0f;
  m.step_A = 0.1f;
  m.dwell_s = 0.1f;
  m.repetitions = static_cast<std::uint16_t>(reps);
  m.unload = 1;
  return m;
}

void expect_quiet(palp::Probe& probe) {
  const palp::Status st = probe.status();
  EXPECT_FALSE(st.streaming) << "the stream was left running";
  EXPECT_NE(st.program_state, palp::proto::ProgramState::running) << "the program was left running";
  EXPECT_EQ(st.i_cmd_A, 0.0) << "the coil was left driven";
}

TEST_F(Recorder, AStreamKeepsExactlyItsDurationOfSamplesWithHealthAndNoGapsInTheSidecar) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  std::vector<palp::RecordProgress> seen;
  const auto r = palp::record(probe, {.out = out("s"), .rate_Hz = 2000, .duration_s = 0.25,
                                      .progress = [&](const palp::RecordProgress& p) { seen.push_back(p); }});
  EXPECT_TRUE(r.written);
  EXPECT_EQ(r.csv, out("s.csv"));
  EXPECT_EQ(r.samples, 500u);  // 0.25 s x 2000 Hz
  EXPECT_EQ(r.samples_missing, 0u);
  EXPECT_FALSE(r.interrupted);
  EXPECT_FALSE(r.program);
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(seen.back().finished);
  EXPECT_EQ(seen.back().samples, 500u);
  EXPECT_EQ(seen.back().expected_samples, 500u);

  const palp::Recording rec = palp::read_recording(out("s.csv"));
  ASSERT_EQ(rec.size(), 500u);
  ASSERT_TRUE(rec.sample_index);
  EXPECT_EQ(rec.sample_index->front(), 0u);
  EXPECT_EQ(rec.sample_index->back(), 499u);
  const auto& extra = rec.sidecar->extra;
  EXPECT_EQ(extra["program_reason"], "no program ran");
  EXPECT_EQ(extra["gaps"], json::array());
  EXPECT_EQ(extra["samples_missing"], 0);
  EXPECT_EQ(extra["interrupted"], false);
  EXPECT_TRUE(extra["health"]["device"].is_object());
  EXPECT_GE(extra["health"]["host"]["samples_received"].get<std::uint64_t>(), 500u);
  EXPECT_DOUBLE_EQ(extra["stream"]["rate_Hz"].get<double>(), 2000.0);
  EXPECT_TRUE(rec.sidecar->device["params"].contains("current_clamp_A"));
  expect_quiet(probe);
}

TEST_F(Recorder, FramesTheSimulatorDropsAreGapRecordsThatAccountForEveryMissingSample) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  ASSERT_EQ(sim.control("drop-frames 5"), "ok");
  const auto r = palp::record(probe, {.out = out("g"), .rate_Hz = 2000, .duration_s = 2.0});
  const palp::Recording rec = palp::read_recording(out("g.csv"));
  const json& gaps = rec.sidecar->extra["gaps"];
  ASSERT_GT(gaps.size(), 0u);
  EXPECT_EQ(gaps.size(), r.gaps);
  std::uint64_t missing = 0, transport = 0, whole_batches = 0;
  for (const auto& g : gaps) {  // a loaded machine may add host-queue gaps: only count those
    missing += g["count"].get<std::uint64_t>();
    if (g["source"] != "transport") continue;
    ++transport;
    whole_batches += g["count"].get<std::uint64_t>() % 40 == 0;  // a dropped frame: 40 samples
  }
  EXPECT_GT(transport, 0u) << gaps.dump();
  EXPECT_EQ(whole_batches, transport) << gaps.dump();
  EXPECT_EQ(missing, r.samples_missing);
  EXPECT_EQ(rec.sidecar->extra["samples_missing"], missing);
  EXPECT_EQ(rec.size(), r.samples);
  // every index below the end is either a row or in a gap
  EXPECT_GE(r.samples + r.samples_missing, 4000u);  // 2 s x 2000 Hz
  EXPECT_LT(r.samples, 4000u);
  EXPECT_EQ(rec.sidecar->extra["health"]["host"]["gaps"].get<std::uint64_t>(), gaps.size());
}

TEST_F(Recorder, ACancelStopsTheProgramAndTheStreamAndLeavesACompleteRecording) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  palp::Probe probe(sim.transport());
  std::atomic<std::uint64_t> samples{0};
  const auto r = palp::record(probe, {.out = out("c"), .rate_Hz = 1000, .program = ramp(100),
                                      .cancelled = [&] { return samples.load() >= 300; },
                                      .progress = [&](const palp::RecordProgress& p) { samples = p.samples; }});
  EXPECT_TRUE(r.interrupted);
  ASSERT_TRUE(r.program);
  EXPECT_EQ(r.program->end, palp::proto::ProgramEnd::stopped_by_host);
  EXPECT_GE(r.samples, 300u);
  EXPECT_LT(r.samples, 190'000u) << "it stopped before the program's 190 s";
  expect_quiet(probe);

  const palp::Recording rec = palp::read_recording(out("c.csv"));  // csv_rows and CRC checked
  EXPECT_EQ(rec.size(), r.samples);
  EXPECT_EQ(rec.sidecar->extra["interrupted"], true);
  EXPECT_EQ(rec.sidecar->program["kind"], "ramp");
  EXPECT_EQ(rec.sidecar->program["result"]["end"], "stopped_by_host");
  EXPECT_DOUBLE_EQ(rec.sidecar->program["parameters"]["stop_A"].get<double>(), 1.0);
}

TEST_F(Recorder, AStreamThatFallsSilentMidRunIsAnErrorThatStopsEverythingAndKeepsTheRecording) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  auto log = std::make_shared<palp::test::LossyLink::Log>();
  std::atomic<int> batches{0};
  log->lose_unasked = [&](palp::proto::MessageId id) {  // every batch after the 20th is lost
    return id == palp::proto::MessageId::SampleBatch && ++batches > 20;
  };
  palp::ConnectOptions quick;
  quick.timeout = 500ms;
  palp::Probe probe(std::make_unique<palp::test::LossyLink>(sim.transport(), log), quick);
  // a hold of a day: with the batches lost nothing paces the simulation, so a program that
  // could end in seconds of wall time would end before the stream counts as silent
  palp::HoldProgram hold;
  hold.current_A = 0.2f;
  hold.duration_s = 86400.0f;
  std::string what;
  try {
    palp::record(probe, {.out = out("e"), .rate_Hz = 1000, .program = hold, .reply_timeout_s = 0.5});
    ADD_FAILURE() << "a silent stream was not an error";
  } catch (const palp::TimeoutError& e) {
    what = e.what();
  } catch (const palp::Error& e) {
    ADD_FAILURE() << "not the silent stream's TimeoutError: " << e.what();
  }
  log->lose_unasked = nullptr;
  expect_quiet(probe);

  const palp::Recording rec = palp::read_recording(out("e.csv"));
  EXPECT_GT(rec.size(), 0u);
  ASSERT_TRUE(rec.sidecar->extra.contains("error"));
  EXPECT_EQ(rec.sidecar->extra["error"], what);
  EXPECT_NE(what.find("stream samples"), std::string::npos) << what;
  EXPECT_TRUE(rec.sidecar->program["result"].is_null());
  EXPECT_TRUE(rec.sidecar->program.contains("fault")) << "the program did not end: its fault";
  EXPECT_TRUE(rec.sidecar->extra["health"]["host"].is_object());
}

TEST_F(Recorder, AnExistingRecordingIsRefusedBeforeADeviceIsUsed) {
  std::ofstream(out("x.json")) << "{}";
  try {
    palp::Recorder rec({.out = out("x"), .duration_s = 1});
    FAIL() << "an existing sidecar was not refused";
  } catch (const palp::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(out("x.json").string() + " already exists"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(palp::Recorder({.out = out("y")}), palp::ConfigError) << "a stream needs a duration";
  EXPECT_FALSE(fs::exists(out("y.csv")));
}

/// The lines of the fenced block that follows the line `after` in a Markdown file.
std::string doc_block(const std::string& file, const std::string& after) {
  std::ifstream in(file);
  std::string line, block;
  bool found = false, inside = false;
  while (std::getline(in, line)) {
    if (!found) {
      found = line.rfind(after, 0) == 0;
    } else if (!inside) {
      inside = line.rfind("```", 0) == 0;
    } else if (line.rfind("```", 0) == 0) {
      return block;
    } else {
      block += line + "\n";
    }
  }
  ADD_FAILURE() << file << " has no fenced block after a line starting " << after;
  return block;
}

TEST_F(Recorder, TheRecordingFormatDocsExampleHasExactlyTheKeysInOrderAndTheHeaderTheRecorderWrites) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  palp::Probe probe(sim.transport());
  palp::record(probe, {.out = out("run"), .rate_Hz = 1000, .program = ramp(1), .zero_current = true,
                       .zero_pressure = true, .zero_s = 0.05});
  const std::string doc = std::string(PALP_SOURCE_DIR) + "/docs/recording-format.md";
  const auto real = palp::test::read_ordered_json(out("run.json").string());
  const auto example = nlohmann::ordered_json::parse(doc_block(doc, "`run.json`:"));
  EXPECT_EQ(palp::test::key_paths(example), palp::test::key_paths(real))
      << "docs/recording-format.md's run.json is not what the recorder writes; a real one:\n"
      << real.dump(2);
  const std::string csv_example = doc_block(doc, "`run.csv` (");
  EXPECT_EQ(csv_example.substr(0, csv_example.find('\n')), palp::test::first_line(out("run.csv").string()));
}

}  // namespace
