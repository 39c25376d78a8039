// SPDX-License-Identifier: Apache-2.0
// The sidecar: every field round-trips (an unknown stroke origin as null with its reason, unknown
// keys kept), the writer fills what it knows, and a malformed sidecar is refused with the key or
// the line and column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "palp/error.hpp"
#include "palp/recording.hpp"
#include "test_recording_util.hpp"

using nlohmann::json;
using palp::ConfigError;
using palp::read_recording;
using palp::RecordingWriter;
using palp::Sidecar;
using palp_test::expect_recording_error;
using palp_test::read_text;
using palp_test::TempDir;
using palp_test::write_text;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::MatchesRegex;

namespace {

Sidecar full_sidecar() {
  Sidecar s;
  s.sdk_version = "9.8.7";
  s.created_utc = "2025-01-31T14:05:09Z";
  s.program = {{"kind", "ramp"}, {"start_A", 0.5}, {"step_A", 0.01},
               {"dwell_s", 0.1}, {"top_A", 3.0},   {"repetitions", 3}};
  s.device = {{"serial", "PALP-0042"}, {"firmware_version", "1.2.3"}, {"board", "stm32g474"}};
  s.calibration = {{"kf_N_per_A", 2.918}, {"pressure_offsets_Pa", {1.5, -0.25, 0, 0, 0, 0}}};
  s.stroke_origin_z_mm_reason = "not homed before this run";
  s.zeroing = json::array({{{"what", "current_offset"},
                            {"t_device_s", 1.5},
                            {"values", {0.0021}},
                            {"values_unit", "A"},
                            {"committed", false}}});
  s.extra = {{"operator", "AB"}, {"robot_pose", {{"x_mm", 12.5}, {"y_mm", -3.0}}}};
  return s;
}

/// Writes a one-row recording with this sidecar to dir/run and returns the sidecar read back.
Sidecar round_trip(const TempDir& dir, const Sidecar& s) {
  RecordingWriter w(dir / "run", {.overwrite = palp::Overwrite::yes});
  w.append({.t_s = 0, .i_A = 0.5, .z_mm = 1.25});
  w.finish(s);
  return read_recording(dir / "run.csv").sidecar.value();
}

std::vector<std::string> top_level_keys(const std::string& text) {
  std::vector<std::string> keys;
  const auto doc = nlohmann::ordered_json::parse(text);
  for (const auto& item : doc.items()) keys.push_back(item.key());
  return keys;
}

/// A valid sidecar document with one key replaced (or removed, with a discarded value).
std::string document_with(const std::string& key, const json& value) {
  json d = {{"schema", "palp.recording/1"}, {"sdk_version", "0.1.0"}, {"stroke_origin_z_mm", 1.0}};
  if (value.is_discarded())
    d.erase(key);
  else
    d[key] = value;
  return d.dump();
}

void expect_sidecar_refused(const TempDir& dir, const std::string& text, const std::string& problem,
                            std::size_t line = 0) {
  const auto path = dir / "bad.json";
  write_text(path, text);
  expect_recording_error([&] { palp::read_sidecar(path); }, path, line, problem);
}

}  // namespace

TEST(RecordingSidecar, UnknownStrokeOriginRoundTripsAsNullWithItsReason) {
  TempDir dir;
  const Sidecar in = full_sidecar();
  const Sidecar out = round_trip(dir, in);
  EXPECT_EQ(out.sdk_version, in.sdk_version);
  EXPECT_EQ(out.created_utc, in.created_utc);
  EXPECT_EQ(out.program, in.program);
  EXPECT_EQ(out.device, in.device);
  EXPECT_EQ(out.calibration, in.calibration);
  EXPECT_FALSE(out.stroke_origin_z_mm.has_value());
  EXPECT_EQ(out.stroke_origin_z_mm_reason, "not homed before this run");
  EXPECT_EQ(out.zeroing, in.zeroing);
  EXPECT_EQ(out.extra, in.extra);
  EXPECT_EQ(out.csv_rows, 1u);
  EXPECT_EQ(out.csv_crc32, 0xbabd1a61u);  // python3: zlib.crc32(open("run.csv", "rb").read())

  const std::string text = read_text(dir / "run.json");
  EXPECT_THAT(text, HasSubstr("\n  \"stroke_origin_z_mm\": null,\n"
                              "  \"stroke_origin_z_mm_reason\": \"not homed before this run\",\n"));
  EXPECT_THAT(top_level_keys(text),
              ElementsAre("schema", "sdk_version", "created_utc", "program", "device",
                          "calibration", "stroke_origin_z_mm", "stroke_origin_z_mm_reason",
                          "zeroing", "csv_rows", "csv_crc32", "operator", "robot_pose"));
  EXPECT_EQ(text.find("NaN"), std::string::npos);
}

TEST(RecordingSidecar, KnownStrokeOriginRoundTripsWithoutAReason) {
  TempDir dir;
  Sidecar in = full_sidecar();
  in.stroke_origin_z_mm = -12.345;
  in.stroke_origin_z_mm_reason.clear();
  const Sidecar out = round_trip(dir, in);
  EXPECT_EQ(out.stroke_origin_z_mm, -12.345);
  EXPECT_EQ(read_text(dir / "run.json").find("stroke_origin_z_mm_reason"), std::string::npos);
}

TEST(RecordingSidecar, WriterFillsVersionDateAndReasonsForWhatItWasNotGiven) {
  TempDir dir;
  const Sidecar out = round_trip(dir, Sidecar{});
  EXPECT_THAT(out.sdk_version, MatchesRegex("[0-9]+\\.[0-9]+\\.[0-9]+"));
  EXPECT_THAT(out.created_utc, MatchesRegex("20[0-9][0-9]-[01][0-9]-[0-3][0-9]T[0-2][0-9]:"
                                            "[0-5][0-9]:[0-6][0-9]Z"));
  EXPECT_TRUE(out.program.is_null());
  EXPECT_TRUE(out.device.is_null());
  EXPECT_TRUE(out.calibration.is_null());
  EXPECT_EQ(out.extra, json({{"program_reason", "not given to the recording writer"},
                             {"device_reason", "not given to the recording writer"},
                             {"calibration_reason", "not given to the recording writer"}}));
  EXPECT_EQ(out.stroke_origin_z_mm_reason, "not given to the recording writer");
  EXPECT_EQ(out.zeroing, json::array());
  EXPECT_THAT(
      top_level_keys(read_text(dir / "run.json")),
      ElementsAre("schema", "sdk_version", "created_utc", "program", "program_reason", "device",
                  "device_reason", "calibration", "calibration_reason", "stroke_origin_z_mm",
                  "stroke_origin_z_mm_reason", "zeroing", "csv_rows", "csv_crc32"));
}

TEST(RecordingSidecar, AdlHooksConvertBothWays) {
  Sidecar in = full_sidecar();
  in.csv_rows = 7;
  in.csv_crc32 = 0xdeadbeef;
  const json j = in;
  EXPECT_EQ(j["schema"], "palp.recording/1");
  EXPECT_EQ(j["csv_crc32"], "deadbeef");
  const Sidecar out = j.get<Sidecar>();
  EXPECT_EQ(out.program, in.program);
  EXPECT_EQ(out.extra, in.extra);
  EXPECT_EQ(out.csv_rows, 7u);
  EXPECT_EQ(out.csv_crc32, 0xdeadbeefu);
}

// The position is where the parser noticed: the end of the offending token.
TEST(RecordingSidecar, InvalidJsonGivesTheLineAndColumn) {
  TempDir dir;
  expect_sidecar_refused(dir,
                         "{\n  \"schema\": \"palp.recording/1\"\n  \"sdk_version\": \"1\"\n}\n",
                         "not valid JSON at column 15: syntax error while parsing object - "
                         "unexpected string literal; expected '}'",
                         3);
  expect_sidecar_refused(dir, "{\"schema\": \"palp.recording/1\",\n\"stroke_origin_z_mm\": NaN}",
                         "not valid JSON at column 23: syntax error while parsing value - "
                         "invalid literal; last read: '\"stroke_origin_z_mm\": N'",
                         2);
}

TEST(RecordingSidecar, WrongTypesNameTheKey) {
  TempDir dir;
  const json absent(json::value_t::discarded);
  expect_sidecar_refused(dir, "[1]", "the sidecar must be a JSON object, not an array");
  expect_sidecar_refused(dir, document_with("sdk_version", 5),
                         "\"sdk_version\" must be a string, not a number (5)");
  expect_sidecar_refused(dir, document_with("sdk_version", absent),
                         "the key \"sdk_version\" is missing");
  expect_sidecar_refused(dir, document_with("program", json::array({1, 2})),
                         "\"program\" must be an object or null, not an array");
  expect_sidecar_refused(dir, document_with("zeroing", json::object()),
                         "\"zeroing\" must be an array, not an object");
  expect_sidecar_refused(dir, document_with("zeroing", json::array({1})),
                         "\"zeroing[0]\" must be an object, not a number (1)");
  expect_sidecar_refused(dir, document_with("stroke_origin_z_mm", "3 mm"),
                         "\"stroke_origin_z_mm\" must be a number or null, not a string "
                         "(\"3 mm\")");
  expect_sidecar_refused(dir, document_with("csv_rows", -1),
                         "\"csv_rows\" must be a whole number >= 0, not a number (-1)");
  expect_sidecar_refused(dir, document_with("csv_crc32", "xyz"),
                         "\"csv_crc32\" must be a string of 8 hex digits, not a string (\"xyz\")");
}

TEST(RecordingSidecar, UnknownStrokeOriginNeedsItsReason) {
  TempDir dir;
  expect_sidecar_refused(dir, document_with("stroke_origin_z_mm", nullptr),
                         "\"stroke_origin_z_mm\" is null without a \"stroke_origin_z_mm_reason\" "
                         "saying why");
  expect_sidecar_refused(dir, document_with("stroke_origin_z_mm", json(json::value_t::discarded)),
                         "the key \"stroke_origin_z_mm\" is missing (a number, or null with "
                         "\"stroke_origin_z_mm_reason\")");
}

TEST(RecordingSidecar, SchemaMustBeThisOne) {
  TempDir dir;
  expect_sidecar_refused(dir, document_with("schema", json(json::value_t::discarded)),
                         "the key \"schema\" is missing; a palp recording sidecar has "
                         "\"schema\": \"palp.recording/1\"");
  expect_sidecar_refused(dir, document_with("schema", "other/1"),
                         "\"schema\" is \"other/1\", not \"palp.recording/1\": this is not a palp "
                         "recording sidecar");
  expect_sidecar_refused(dir, document_with("schema", "palp.recording/2"),
                         "\"schema\" is \"palp.recording/2\", which this SDK cannot read (it "
                         "reads palp.recording/1); update the SDK");
}

TEST(RecordingSidecar, MalformedSidecarBesideACsvNamesTheSidecar) {
  TempDir dir;
  write_text(dir / "run.csv", "t_s,i_A,z_mm\n0,1,2\n");
  write_text(dir / "run.json", document_with("device", "probe 7"));
  expect_recording_error([&] { read_recording(dir / "run.csv"); }, dir / "run.json", 0,
                         "\"device\" must be an object or null, not a string (\"probe 7\")");
  EXPECT_EQ(read_recording(dir / "run.csv", {.read_sidecar = false}).size(), 1u);
}

TEST(RecordingSidecar, UnwritableSidecarIsRefusedBeforeAnythingIsRenamed) {
  TempDir dir;
  RecordingWriter w(dir / "run");
  w.append({.t_s = 0, .i_A = 1, .z_mm = 2});
  const auto expect_refused = [&](const Sidecar& s, const std::string& message) {
    try {
      w.finish(s);
      ADD_FAILURE() << "no ConfigError";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
    EXPECT_EQ(dir.files().size(), 1u) << "only the temporary CSV";
  };
  Sidecar s;
  s.extra = {{"schema", "mine/1"}};
  expect_refused(s,
                 "Sidecar::extra holds the key \"schema\", which the sidecar writes from its "
                 "own field; set that field instead");
  s = {};
  s.program = 5;
  expect_refused(s, "Sidecar::program must be a JSON object or null, not a number (5)");
  s = {};
  s.stroke_origin_z_mm = std::nan("");
  expect_refused(s,
                 "Sidecar::stroke_origin_z_mm is nan; use nullopt with a "
                 "stroke_origin_z_mm_reason when it is unknown");
  w.append({.t_s = 1, .i_A = 1, .z_mm = 2});  // still open
  w.finish(full_sidecar());
  EXPECT_EQ(read_recording(dir / "run.csv").sidecar->device, full_sidecar().device);
}
