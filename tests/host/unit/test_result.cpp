// SPDX-License-Identifier: Apache-2.0
// Result directories (palp/result.hpp): written whole into place, read back with the same numbers,
// the issue's JSON keys in lab units, and errors that name the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "palp/error.hpp"
#include "palp/result.hpp"
#include "test_result_synth.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::HasSubstr;

using palp_test::kEstar;
using palp_test::synthetic_run;

class ResultDir : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("palp-result-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(ResultDir, WrittenRunReadsBackWithTheSameRecordingSettingsAndAnalysis) {
  const palp::IndentationRun run = synthetic_run();
  ASSERT_TRUE(run.analysis) << run.analysis_reason;
  const fs::path dir = palp::write_result(root_ / "solid-p3", run);
  EXPECT_TRUE(fs::exists(dir / "result.json"));
  EXPECT_TRUE(fs::exists(dir / "indentation.csv"));
  EXPECT_TRUE(fs::exists(dir / "indentation.json"));

  const palp::LoadedResult loaded = palp::load_result(dir);
  EXPECT_EQ(loaded.experiment, "indentation");
  EXPECT_EQ(loaded.summary["schema"], "palp.result/1");
  EXPECT_EQ(loaded.summary["sdk_version"], palp::sdk_version());
  EXPECT_EQ(loaded.summary["firmware_version"], "1.2.3");
  EXPECT_EQ(loaded.summary["device"]["serial"], "SIM-0001");
  EXPECT_DOUBLE_EQ(loaded.summary["parameters"]["dwell_s"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(loaded.summary["parameters"]["displacement_limit_mm"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(loaded.summary["parameters"]["analysis"]["kv_N_per_mm"].get<double>(), 0.0439);
  ASSERT_EQ(loaded.recordings.size(), 1u);
  const palp::Recording& r = loaded.recordings[0].second;
  ASSERT_EQ(r.size(), run.recording.size());
  EXPECT_EQ(r.z_mm, run.recording.z_mm);  // bit-exact
  EXPECT_EQ(r.rep, run.recording.rep);

  // re-analysed from the files: the same numbers as the run's own analysis
  const palp::IndentationRun again = palp::indentation_run_of(loaded);
  ASSERT_TRUE(again.analysis) << again.analysis_reason;
  EXPECT_DOUBLE_EQ(*again.analysis->delta0_m.value, *run.analysis->delta0_m.value);
  EXPECT_EQ(again.settings.repetitions, 2);
  EXPECT_DOUBLE_EQ(again.settings.analysis.spring_N_per_m, 43.9);
}

TEST_F(ResultDir, SummaryCarriesTheIssueKeysInLabUnitsWithTheKnownModulus) {
  const palp::IndentationRun run = synthetic_run();
  const fs::path dir = palp::write_result(root_ / "r", run);
  const json a = palp::load_result(dir).summary["analysis"];
  for (const char* key : {"contact_point_mm", "k_linear_N_per_mm", "r2_linear", "E_star_hertz_Pa",
                          "r2_hertz", "E_star_sneddon_Pa", "r2_sneddon", "model_by_aic", "delta0_mm",
                          "k_tangent_N_per_mm", "k_fd_N_per_mm", "k_ls_window_N_per_mm",
                          "k_fd_paper_N_per_mm", "k_at_depth_N_per_mm", "params"})
    EXPECT_TRUE(a.contains(key)) << key;
  EXPECT_NEAR(a["E_star_hertz_Pa"].get<double>(), kEstar, 0.01 * kEstar);
  EXPECT_TRUE(a["E_star_hertz_Pa_se"].is_number());
  EXPECT_TRUE(a["delta0_mm_sd"].is_number());  // two repetitions
  EXPECT_NEAR(a["contact_point_mm"].get<double>(), 25.0, 0.005);
  EXPECT_DOUBLE_EQ(a["params"]["kf_N_per_A"].get<double>(), 2.918);
  EXPECT_DOUBLE_EQ(a["params"]["bias_force_N"].get<double>(), 2.918 * 0.5);
  EXPECT_TRUE(a["params"]["thickness_mm"].is_null());
  EXPECT_TRUE(a["params"].contains("thickness_mm_reason"));
  // the tangent stiffness at the issue's depths
  EXPECT_TRUE(a["k_at_depth_N_per_mm"].contains("1_mm"));
  EXPECT_TRUE(a["k_at_depth_N_per_mm"].contains("4_mm"));
  // delta0's standard error through the fit's E* (delta method): d0 ~ E*^(-2/3) for Hertz
  const double se_rel = a["E_star_hertz_Pa_se"].get<double>() / a["E_star_hertz_Pa"].get<double>();
  ASSERT_EQ(a["model_by_aic"], "hertz");
  EXPECT_NEAR(a["delta0_mm_se"].get<double>() / a["delta0_mm"].get<double>(), 2.0 / 3.0 * se_rel,
              0.05 * se_rel);
  EXPECT_NEAR(a["E_hertz_Pa"].get<double>(), 0.75 * a["E_star_hertz_Pa"].get<double>(), 1e-6);
  // model-free descriptors have no fit error: null with the reason
  EXPECT_TRUE(a["k_fd_N_per_mm_se"].is_null());
  EXPECT_EQ(a["k_fd_N_per_mm_se_reason"], "model-free: no fit standard error (see the _sd over repetitions)");
}

TEST_F(ResultDir, ThePressureForceTestGivesEachChannelsKnownSlope) {
  const palp::IndentationRun run = synthetic_run();
  ASSERT_TRUE(run.pressure) << run.pressure_reason;
  const json p = palp::load_result(palp::write_result(root_ / "p", run)).summary["pressure"];
  ASSERT_EQ(p["channels"].size(), 6u);
  for (int m = 0; m < 6; ++m) {
    const json& ch = p["channels"][static_cast<std::size_t>(m)];
    EXPECT_EQ(ch["channel"], m + 1);
    EXPECT_NEAR(ch["slope_Pa_per_N"].get<double>(), 20.0 * (m + 1), 0.01 * 20.0 * (m + 1));
    EXPECT_GT(ch["r2"].get<double>(), 0.999);
  }
  EXPECT_NEAR(p["contact_point_mm"].get<double>(), 25.0, 0.005);
}

TEST_F(ResultDir, AnExistingDirectoryIsRefusedUnlessOverwriteAndThenReplacedWhole) {
  palp::IndentationRun run = synthetic_run();
  const fs::path dir = root_ / "r";
  palp::write_result(dir, run);
  try {
    palp::write_result(dir, run);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("already exists"));
  }
  run.settings.repetitions = 7;  // only to tell the two apart
  palp::write_result(dir, run, palp::Overwrite::yes);
  EXPECT_EQ(palp::load_result(dir).summary["parameters"]["reps"], 7);
  // the manifest names exactly the files palp wrote
  std::ifstream manifest(dir / ".palp-files");
  std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "indentation.csv\nindentation.json\nresult.json\n");
  // nothing hidden left beside it
  for (const auto& e : fs::directory_iterator(root_))
    EXPECT_EQ(e.path().filename(), "r") << "left behind: " << e.path();
}

TEST_F(ResultDir, OverwriteKeepsAFileItDidNotWriteAndNamesIt) {
  palp::IndentationRun run = synthetic_run();
  const fs::path dir = root_ / "r";
  palp::write_result(dir, run);
  std::ofstream(dir / "notes.txt") << "the user's";
  run.settings.repetitions = 7;
  try {
    palp::write_result(dir, run, palp::Overwrite::yes);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "notes.txt").string() + " was not written by palp"));
  }
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_EQ(palp::load_result(dir).summary["parameters"]["reps"], 2);  // the old result, whole
  fs::remove(dir / "notes.txt");
  palp::write_result(dir, run, palp::Overwrite::yes);
  EXPECT_EQ(palp::load_result(dir).summary["parameters"]["reps"], 7);
}

TEST_F(ResultDir, OverwriteRefusesADirectoryPalpNeverWroteAndKeepsItsFiles) {
  const fs::path dir = root_ / "mine";
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "result.json") << "{}";  // even one named like palp's
  std::ofstream(dir / "sub" / "data.txt") << "the user's";
  try {
    palp::write_result(dir, synthetic_run(), palp::Overwrite::yes);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(dir.string() + " is not a result directory palp wrote"));
  }
  EXPECT_TRUE(fs::exists(dir / "sub" / "data.txt"));
  EXPECT_TRUE(fs::exists(dir / "result.json"));
  EXPECT_THROW(palp::check_replaceable(dir), palp::ConfigError);
  EXPECT_NO_THROW(palp::check_replaceable(root_ / "absent"));
}

TEST_F(ResultDir, AnUnbondedThicknessCorrectionIsReadBackAsUnbonded) {
  palp::IndentationRun run = synthetic_run();
  run.settings.analysis.thickness =
      palp::analysis::Thickness{15e-3, palp::analysis::Bonding::unbonded};
  const palp::LoadedResult loaded = palp::load_result(palp::write_result(root_ / "t", run));
  EXPECT_EQ(loaded.summary["parameters"]["analysis"]["bonding"], "unbonded");
  const palp::IndentationRun again = palp::indentation_run_of(loaded);
  ASSERT_TRUE(again.settings.analysis.thickness);
  EXPECT_DOUBLE_EQ(again.settings.analysis.thickness->thickness_m, 15e-3);
  EXPECT_EQ(again.settings.analysis.thickness->bonding, palp::analysis::Bonding::unbonded);
}

TEST_F(ResultDir, ARunWithoutSamplesWritesNothing) {
  palp::IndentationRun run;
  EXPECT_THROW(palp::write_result(root_ / "empty", run), palp::ConfigError);
  EXPECT_FALSE(fs::exists(root_ / "empty"));
  EXPECT_TRUE(fs::is_empty(root_));
}

TEST_F(ResultDir, LoadErrorsNameTheFileAndTheProblem) {
  auto message = [](const fs::path& dir) -> std::string {
    try {
      palp::load_result(dir);
    } catch (const palp::RecordingError& e) {
      return e.what();
    }
    return "no RecordingError";
  };
  EXPECT_THAT(message(root_ / "nowhere"), HasSubstr("no such result directory"));
  fs::create_directories(root_ / "a");
  EXPECT_THAT(message(root_ / "a"), HasSubstr("no result.json"));

  const fs::path dir = palp::write_result(root_ / "b", synthetic_run());
  const std::string file = (dir / "result.json").string();
  std::ofstream(dir / "result.json") << "{\"schema\": \"palp.result/1\",\n \"experiment\": ";
  EXPECT_THAT(message(dir), HasSubstr(file));
  EXPECT_THAT(message(dir), HasSubstr("invalid JSON"));
  std::ofstream(dir / "result.json") << R"({"schema": "palp.result/9", "experiment": "indentation"})";
  EXPECT_THAT(message(dir), HasSubstr("schema is \"palp.result/9\", expected \"palp.result/1\""));
  std::ofstream(dir / "result.json") << R"({"schema": "palp.result/1", "experiment": "indentation"})";
  EXPECT_THAT(message(dir), HasSubstr("missing key \"recordings\""));
  std::ofstream(dir / "result.json")
      << R"({"schema": "palp.result/1", "experiment": "indentation", "recordings": ["../x.csv"]})";
  EXPECT_THAT(message(dir), HasSubstr("not a file name inside the result directory"));
  std::ofstream(dir / "result.json")
      << R"({"schema": "palp.result/1", "experiment": "indentation", "recordings": ["gone.csv"]})";
  EXPECT_THAT(message(dir), HasSubstr((dir / "gone.csv").string() + ": listed in result.json but missing"));
}

TEST_F(ResultDir, AnIncompleteParameterBlockIsARecordingErrorNamingTheFileAndTheKey) {
  const fs::path dir = palp::write_result(root_ / "b", synthetic_run());
  palp::LoadedResult loaded = palp::load_result(dir);
  loaded.summary["parameters"]["analysis"].erase("kv_N_per_mm");
  try {
    palp::indentation_run_of(loaded);
    FAIL() << "no RecordingError";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "result.json").string()));
    EXPECT_THAT(e.what(), HasSubstr("missing key \"parameters.analysis.kv_N_per_mm\""));
  }
}

TEST_F(ResultDir, AnIncompleteRunBlockIsARecordingErrorNamingTheFileAndTheKey) {
  const fs::path dir = palp::write_result(root_ / "r", synthetic_run());
  palp::LoadedResult loaded = palp::load_result(dir);
  EXPECT_EQ(palp::indentation_run_of(loaded).samples_missing, loaded.summary["run"]["samples_missing"].get<std::uint64_t>());
  loaded.summary["run"].erase("samples_missing");
  try {
    palp::indentation_run_of(loaded);
    FAIL() << "no RecordingError";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "result.json").string()));
    EXPECT_THAT(e.what(), HasSubstr("missing key \"run.samples_missing\""));
  }
}

TEST(IndentationSettings, PresetsAreTheIssuesProtocols) {
  const auto one = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
  const auto two = palp::IndentationSettings::preset(palp::IndentationPreset::two_d);
  for (const auto* s : {&one, &two}) {
    EXPECT_DOUBLE_EQ(s->start_A, 0.5);
    EXPECT_DOUBLE_EQ(s->stop_A, 3.0);
    EXPECT_DOUBLE_EQ(s->step_A, 0.01);
    EXPECT_TRUE(s->unload);
    EXPECT_DOUBLE_EQ(s->displacement_limit_m, 5e-3);
    EXPECT_LE(s->stream_rate_Hz, 1000.0);
  }
  EXPECT_DOUBLE_EQ(one.dwell_s, 0.1);
  EXPECT_EQ(one.repetitions, 5);
  EXPECT_DOUBLE_EQ(two.dwell_s, 0.025);
  EXPECT_EQ(two.repetitions, 3);
  const palp::RampProgram m = one.ramp_program();
  EXPECT_EQ(m.displacement_limit_counts, 5000u);
  EXPECT_EQ(m.repetitions, 5);
  EXPECT_EQ(m.unload, 1);
  // 251 levels up, 250 down per repetition (the firmware's schedule), 100 ms each
  EXPECT_NEAR(one.ramp_duration_s(), 5 * 501 * 0.1, 1e-9);
}

TEST(IndentationSettings, BadSettingsAreOneLineConfigErrorsNamingTheSetting) {
  auto message = [](auto change) -> std::string {
    auto s = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
    change(s);
    try {
      s.validate();
    } catch (const palp::ConfigError& e) {
      return e.what();
    }
    return "valid";
  };
  EXPECT_EQ(message([](auto& s) { s.stream_rate_Hz = 2000; }),
            "indentation settings: stream_rate_Hz must lie in (0, 1000] Hz");
  EXPECT_EQ(message([](auto& s) { s.stop_A = 0.4; }),
            "indentation settings: stop_A must be above start_A (the ramp pushes into the specimen)");
  EXPECT_EQ(message([](auto& s) { s.repetitions = 0; }),
            "indentation settings: repetitions must lie in 1..1000");
  EXPECT_EQ(message([](auto& s) { s.displacement_limit_m = NAN; }),
            "indentation settings: displacement_limit_m is nan, not a finite number");
  EXPECT_EQ(message([](auto& s) { s.displacement_limit_m = 0.2; }),
            "indentation settings: displacement_limit_m must lie in 0..0.1 m (0: no limit)");
  EXPECT_EQ(message([](auto&) {}), "valid");
}

TEST(IndentationSettingsJson, EverySettingReadsBackAsWritten) {
  palp::IndentationSettings s = palp::IndentationSettings::preset(palp::IndentationPreset::one_d);
  s.start_A = 0.6;
  s.stop_A = 2.25;
  s.step_A = 0.02;
  s.dwell_s = 0.2;
  s.repetitions = 3;
  s.unload = false;
  s.displacement_limit_m = 3.5e-3;
  s.stream_rate_Hz = 500;
  s.zero_pressure = false;
  s.zero_pressure_s = 0.75;
  s.settle_s = 2.5;
  auto& p = s.analysis;
  p.force_constant_N_per_A = 3.1;
  p.contact_current_A = 0.45;
  p.spring_N_per_m = 51.2;
  p.tip_radius_m = 3e-3;
  p.poisson = 0.45;
  p.bias_current_A = 1.25;
  p.thickness = palp::analysis::Thickness{12e-3, palp::analysis::Bonding::bonded};
  p.window_lo_m = 0.3e-3;
  p.window_hi_m = 0.9e-3;
  p.local_half_width_m = 40e-6;
  p.tangent_depths_m = {0.5e-3, 1.5e-3};
  p.min_points = 17;
  p.force_noise_N = 0.002;

  const palp::IndentationSettings r = palp::indentation_settings_from_json(palp::indentation_settings_json(s));
  EXPECT_EQ(r.start_A, 0.6);
  EXPECT_EQ(r.stop_A, 2.25);
  EXPECT_EQ(r.step_A, 0.02);
  EXPECT_EQ(r.dwell_s, 0.2);
  EXPECT_EQ(r.repetitions, 3);
  EXPECT_FALSE(r.unload);
  EXPECT_DOUBLE_EQ(r.displacement_limit_m, 3.5e-3);
  EXPECT_EQ(r.stream_rate_Hz, 500);
  EXPECT_FALSE(r.zero_pressure);
  EXPECT_EQ(r.zero_pressure_s, 0.75);
  EXPECT_EQ(r.settle_s, 2.5);
  const auto& q = r.analysis;
  EXPECT_EQ(q.force_constant_N_per_A, 3.1);
  EXPECT_EQ(q.contact_current_A, 0.45);
  EXPECT_DOUBLE_EQ(q.spring_N_per_m, 51.2);
  EXPECT_DOUBLE_EQ(q.tip_radius_m, 3e-3);
  EXPECT_EQ(q.poisson, 0.45);
  EXPECT_EQ(q.bias_current_A, 1.25);
  ASSERT_TRUE(q.thickness);
  EXPECT_DOUBLE_EQ(q.thickness->thickness_m, 12e-3);
  EXPECT_EQ(q.thickness->bonding, palp::analysis::Bonding::bonded);
  EXPECT_DOUBLE_EQ(q.window_lo_m, 0.3e-3);
  EXPECT_DOUBLE_EQ(q.window_hi_m, 0.9e-3);
  EXPECT_DOUBLE_EQ(q.local_half_width_m, 40e-6);
  ASSERT_EQ(q.tangent_depths_m.size(), 2u);
  EXPECT_DOUBLE_EQ(q.tangent_depths_m[0], 0.5e-3);
  EXPECT_DOUBLE_EQ(q.tangent_depths_m[1], 1.5e-3);
  EXPECT_EQ(q.min_points, 17);
  EXPECT_EQ(q.force_noise_N, 0.002);
}

TEST(IndentationSettingsJson, AMissingOrMistypedSettingIsNamedWithItsPath) {
  auto message = [](const json& j) -> std::string {
    try {
      palp::indentation_settings_from_json(j, "parameters.");
    } catch (const palp::ConfigError& e) {
      return e.what();
    }
    return "no ConfigError";
  };
  json j = palp::indentation_settings_json(palp::IndentationSettings{});
  j["analysis"].erase("poisson");
  EXPECT_EQ(message(j), "missing key \"parameters.analysis.poisson\"");
  j["analysis"]["poisson"] = "half";
  EXPECT_EQ(message(j), "\"parameters.analysis.poisson\" is not a number");
  j["analysis"]["poisson"] = 0.5;
  j["analysis"]["tangent_depths_mm"] = json::array({1.0, "two"});
  EXPECT_EQ(message(j), "\"parameters.analysis.tangent_depths_mm\" is not an array of numbers");
}

TEST(DeviceJson, EveryDeviceInfoFieldReadsBackAsWritten) {
  palp::DeviceInfo d;
  d.serial = "PALP-0042";
  d.board = "stm32g474";
  d.git_hash = "3f9c2e1";
  d.firmware_version = "1.2.0";
  d.protocol_major = 1;
  d.protocol_minor = 3;
  d.schema_hash = 0xDEADBEEF;
  d.capabilities = 0x49;
  d.max_current_A = 3.2;
  d.control_rate_Hz = 20000;
  d.max_stream_rate_Hz = 10000;
  d.heartbeat_timeout_s = 0.5;
  d.max_payload = 1024;
  const json j = palp::device_json(d);
  EXPECT_EQ(j["protocol"], "1.3");
  EXPECT_EQ(j["max_payload_bytes"], 1024);
  const palp::DeviceInfo r = palp::device_info_from_json(j, "device");
  EXPECT_EQ(r.serial, d.serial);
  EXPECT_EQ(r.board, d.board);
  EXPECT_EQ(r.git_hash, d.git_hash);
  EXPECT_EQ(r.firmware_version, d.firmware_version);
  EXPECT_EQ(r.protocol_major, 1);
  EXPECT_EQ(r.protocol_minor, 3);
  EXPECT_EQ(r.schema_hash, 0xDEADBEEFu);
  EXPECT_EQ(r.capabilities, 0x49u);
  EXPECT_EQ(r.max_current_A, 3.2);
  EXPECT_EQ(r.control_rate_Hz, 20000);
  EXPECT_EQ(r.max_stream_rate_Hz, 10000);
  EXPECT_EQ(r.heartbeat_timeout_s, 0.5);
  EXPECT_EQ(r.max_payload, 1024u);
}

TEST_F(ResultDir, ASidecarFromTheOldPalpctlGivesItsDeviceWithProtocolAndCapabilities) {
  // run.json as palpctl stream wrote it before its device block was the SDK's
  const fs::path file = root_ / "run.json";
  std::ofstream(file) << R"json({
  "schema": "palp.recording/1",
  "sdk_version": "0.1.0",
  "created_utc": "2026-11-20T10:00:00Z",
  "program": null,
  "program_reason": "palpctl stream: no program ran",
  "device": {
    "board": "palp-sim",
    "control_rate_Hz": 20000.0,
    "firmware_version": "0.1.0",
    "git_hash": "sim",
    "heartbeat_timeout_s": 0.5,
    "max_current_A": 4.0,
    "max_payload_bytes": 1024,
    "max_stream_rate_Hz": 10000.0,
    "params": {"current_clamp_A": 3.2},
    "pressure_channels": 6,
    "protocol_version": "1.0",
    "schema_hash": 305419896,
    "serial": "SIM-0001",
    "simulated": true,
    "uri": "sim://127.0.0.1:7070"
  },
  "calibration": null,
  "calibration_reason": "not read",
  "stroke_origin_z_mm": null,
  "stroke_origin_z_mm_reason": "the device's stroke origin is not homed (palpctl calibrate home)",
  "zeroing": []
})json";
  const palp::Sidecar side = palp::read_sidecar(file);
  const palp::DeviceInfo d = palp::device_info_from_json(side.device, "run.json: device");
  EXPECT_EQ(d.serial, "SIM-0001");
  EXPECT_EQ(d.board, "palp-sim");
  EXPECT_EQ(d.protocol_major, 1);
  EXPECT_EQ(d.protocol_minor, 0);
  EXPECT_EQ(d.schema_hash, 305419896u);
  EXPECT_EQ(d.max_payload, 1024u);
  EXPECT_EQ(d.control_rate_Hz, 20000.0);
  EXPECT_TRUE(d.has(palp::proto::Capability::simulated));
  EXPECT_TRUE(d.has(palp::proto::Capability::pressure));
  EXPECT_FALSE(d.has(palp::proto::Capability::hid));
}

TEST(DeviceJson, AProtocolThatIsNotMajorDotMinorIsRefusedByName) {
  try {
    palp::device_info_from_json({{"protocol", "one"}}, "run.json: device");
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "run.json: device: \"protocol\" must be \"major.minor\", not \"one\"");
  }
}

TEST(ProgramJson, ARampIsWrittenInLabUnitsAndReadsBackToTheSameMessage) {
  palp::RampProgram m;
  m.start_A = 0.5f;
  m.stop_A = 3.0f;
  m.step_A = 0.01f;
  m.dwell_s = 0.1f;
  m.repetitions = 5;
  m.unload = 0;
  m.displacement_limit_counts = 4500;
  const json j = palp::program_json(m);
  EXPECT_EQ(j, json::parse(R"({"start_A": 0.5, "stop_A": 3.0, "step_A": 0.01, "dwell_s": 0.1,
                               "reps": 5, "unload": false, "displacement_limit_mm": 4.5})"));
  palp::RampProgram r;
  palp::read_program(j, "ramp", r);
  EXPECT_EQ(r, m);
}

TEST(ProgramJson, SweepAndMultisineReadBackToTheSameMessages) {
  palp::SweepProgram s;
  s.offset_A = 1.25f;
  s.amplitude_A = 0.05f;
  s.start_Hz = 0.5f;
  s.stop_Hz = 40.0f;
  s.step_Hz = 0.25f;
  s.settle_cycles = 7;
  s.settle_min_s = 0.8f;
  s.measure_cycles = 9;
  palp::SweepProgram s2;
  palp::read_program(palp::program_json(s), "sweep", s2);
  EXPECT_EQ(s2, s);

  palp::MultisineProgram m;
  m.offset_A = 1.1f;
  m.fundamental_Hz = 0.1f;
  m.line_first = 5;
  m.line_last = 201;
  m.line_step = 4;
  m.line_amplitude_A = 0.003f;
  m.phase_mode = palp::proto::PhaseMode::schroeder;
  m.phase_seed = 77;
  m.periods = 6;
  const json j = palp::program_json(m);
  EXPECT_EQ(j["phase_mode"], "schroeder");
  EXPECT_EQ(j["line_amplitude_A"], 0.003);  // the f32's shortest decimal
  palp::MultisineProgram m2;
  palp::read_program(j, "multisine", m2);
  EXPECT_EQ(m2, m);
}

TEST(ProgramJson, AMistypedParameterIsAConfigErrorNamingIt) {
  json j = palp::program_json(palp::SweepProgram{});
  j["step_Hz"] = "fast";
  palp::SweepProgram m;
  try {
    palp::read_program(j, "run.json: program.parameters", m);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "run.json: program.parameters: \"step_Hz\" must be a number");
  }
}

}  // namespace
