// SPDX-License-Identifier: Apache-2.0
// Rig and plan files: the documented examples load with the stated values, defaults fill the
// optional keys, a region and an origin + pitch give the same grid, a saved rig reads back, and
// every bad file gives one line naming the file, the key and the problem.
#include "palp/rig.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/protocol/robot_bridge/check.hpp"
#include "robot/robot_convert.hpp"

namespace palp {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The ```json <kind> blocks of docs/rig-and-plan.md, in order.
std::vector<std::string> doc_examples(const std::string& kind) {
  std::ifstream in(std::string(PALP_SOURCE_DIR) + "/docs/rig-and-plan.md");
  std::vector<std::string> out;
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```json " + kind) {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      out.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kMinimalRig = R"({"format_version": 1, "robot_uri": "modbus://127.0.0.1:30005",
  "probe_uri": "sim://127.0.0.1:5000", "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0],
  "safe_height_mm": 5})";

TEST(Rig, DocumentedExampleLoadsInSI) {
  const auto examples = doc_examples("rig");
  ASSERT_EQ(examples.size(), 1u);
  const Rig r = parse_rig(examples[0], "rig-and-plan.md");
  EXPECT_EQ(r.robot_uri, "modbus://172.31.1.147:30005");
  EXPECT_EQ(r.probe_uri, "usb://");
  EXPECT_EQ(r.tool_id, 1);
  EXPECT_DOUBLE_EQ(r.tool_tcp.z_m, 0.2125);
  EXPECT_DOUBLE_EQ(r.safe_height_m, 0.010);
  EXPECT_DOUBLE_EQ(r.approach_speed_m_per_s, 1e-3);
  EXPECT_DOUBLE_EQ(r.travel_speed_m_per_s, 0.020);
  EXPECT_EQ(r.contact_input, 1);
  EXPECT_DOUBLE_EQ(r.contact_threshold_m, 0.2e-3);
  EXPECT_DOUBLE_EQ(r.watch_current_A, 0.6);
  EXPECT_DOUBLE_EQ(r.max_approach_m, 0.010);
  EXPECT_DOUBLE_EQ(r.tip_radius_m, 2.5e-3);
  ASSERT_TRUE(r.work_object.has_value());
  EXPECT_EQ(r.work_object->name, "pad");
  EXPECT_DOUBLE_EQ(r.work_object->pose.x_m, 0.6);
  EXPECT_DOUBLE_EQ(r.work_object->pose.c_rad, std::numbers::pi);
}

TEST(Rig, OptionalKeysTakeTheDocumentedDefaults) {
  const Rig r = parse_rig(kMinimalRig, "rig.json");
  EXPECT_EQ(r.tool_id, 1);
  EXPECT_EQ(r.approach_speed_m_per_s, 1e-3);
  EXPECT_EQ(r.travel_speed_m_per_s, 0.02);
  EXPECT_EQ(r.contact_input, 1);
  EXPECT_EQ(r.contact_threshold_m, 0.2e-3);
  EXPECT_EQ(r.watch_current_A, 0.6);
  EXPECT_EQ(r.max_approach_m, 10e-3);
  EXPECT_EQ(r.tip_radius_m, 2.5e-3);
  EXPECT_FALSE(r.work_object.has_value());
}

TEST(Rig, SavedRigWithItsWorkObjectReadsBack) {
  Rig r = parse_rig(kMinimalRig, "rig.json");
  r.work_object = WorkObject{"pad", Pose{0.61, -0.05, 0.15, 12.5 * kDeg, -3.0 * kDeg, 179.0 * kDeg}};
  r.contact_input = 7;
  const auto path = std::filesystem::path(::testing::TempDir()) /
                    ("palp_rig_" + std::to_string(::getpid()) + ".json");
  save_rig(path, r);
  const Rig back = load_rig(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  ASSERT_TRUE(back.work_object.has_value());
  EXPECT_EQ(back.work_object->name, "pad");
  EXPECT_NEAR(back.work_object->pose.x_m, 0.61, 1e-15);
  EXPECT_NEAR(back.work_object->pose.a_rad, 12.5 * kDeg, 1e-15);
  EXPECT_NEAR(back.work_object->pose.c_rad, 179.0 * kDeg, 1e-15);
  EXPECT_EQ(back.contact_input, 7);
  EXPECT_NEAR(back.safe_height_m, 5e-3, 1e-18);
  EXPECT_NE(rig_to_json(back).find("\"safe_height_mm\": 5.0"), std::string::npos);
}

TEST(Plan, DocumentedExamplesLoadAndDescribeTheSameGrid) {
  const auto examples = doc_examples("plan");
  ASSERT_EQ(examples.size(), 2u);
  const Plan a = parse_plan(examples[0], "a.json");
  const Plan b = parse_plan(examples[1], "b.json");
  EXPECT_EQ(a.work_object, "pad");
  EXPECT_EQ(a.point_count(), 81);
  ASSERT_TRUE(a.contact_E_star_Pa.has_value());
  EXPECT_EQ(*a.contact_E_star_Pa, 3.3e6);
  EXPECT_DOUBLE_EQ(*a.approach_speed_m_per_s, 1e-3);
  EXPECT_FALSE(b.contact_E_star_Pa.has_value());
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) {
      EXPECT_NEAR(a.point_m(r, c).first, b.point_m(r, c).first, 1e-15);
      EXPECT_NEAR(a.point_m(r, c).second, b.point_m(r, c).second, 1e-15);
    }
  // Row 8, column 8 (1-based) of the pad: (80, 75) mm.
  EXPECT_NEAR(a.point_m(7, 7).first, 0.080, 1e-15);
  EXPECT_NEAR(a.point_m(7, 7).second, 0.075, 1e-15);
  EXPECT_NEAR(a.x_m(8), 0.090, 1e-15);
  EXPECT_NEAR(a.y_m(8), 0.085, 1e-15);
  EXPECT_EQ(error_of([&] { a.point_m(9, 0); }), "plan pad 9 x 9: no row 9 (0-based) in a grid of 9");
}

TEST(Rig, BadFilesGiveOneLineWithFileKeyAndProblem) {
  auto rig_error = [](const std::string& text) {
    return error_of([&] { parse_rig(text, "rig.json"); });
  };
  std::string t = kMinimalRig;
  EXPECT_EQ(rig_error(t.substr(0, t.size() - 1) + R"(, "safe_hieght_mm": 3})"),
            "rig.json: safe_hieght_mm: unknown key");
  EXPECT_EQ(rig_error(R"({"format_version": 1, "probe_uri": "usb://"})"),
            "rig.json: robot_uri: missing (required)");
  std::string bad = t;
  bad.replace(bad.find("\"safe_height_mm\": 5"), 19, "\"safe_height_mm\": -2");
  EXPECT_EQ(rig_error(bad), "rig.json: safe_height_mm: must be > 0 mm (got -2)");
  bad = t;
  bad.replace(bad.find("[0, 0, 200, 0, 0, 0]"), 20, "[0, 0, 200]");
  EXPECT_EQ(rig_error(bad), "rig.json: tool_tcp_mm_deg: must be an array of 6 numbers");
  bad = t.substr(0, t.size() - 1) + R"(, "contact_input": 17})";
  EXPECT_EQ(rig_error(bad), "rig.json: contact_input: must be in 1..16 (got 17)");
  bad = t.substr(0, t.size() - 1) + R"(, "work_object": {"name": "pad"}})";
  EXPECT_EQ(rig_error(bad), "rig.json: work_object.pose_mm_deg: missing (required)");
  bad = t.substr(0, t.size() - 1) + R"(, "watch_current_A": "0.6"})";
  EXPECT_EQ(rig_error(bad), "rig.json: watch_current_A: must be a number");
  EXPECT_EQ(rig_error("[1, 2]"), "rig.json: the top level must be a JSON object");
  EXPECT_EQ(error_of([] { load_rig("/nonexistent/rig.json"); }),
            "/nonexistent/rig.json: cannot open: No such file or directory");
}

// One range for tool_id: the rig reader takes exactly the ids the bridge's set_tool takes (the
// reader said 1..16, the bridge 1..15, so 16 passed the rig check and failed at run time).
TEST(Rig, ToolIdTakesExactlyTheIdsTheBridgeTakes0And16Refused) {
  const std::string t = kMinimalRig;
  for (const int id : {0, 1, 15, 16}) {
    const std::string text = t.substr(0, t.size() - 1) + ", \"tool_id\": " + std::to_string(id) + "}";
    const bool rig_takes = error_of([&] { parse_rig(text, "rig.json"); }) == "(no error)";
    const bool bridge_takes = proto::rb::check_command(detail::tool_command(id, Pose{})).accepted();
    EXPECT_EQ(rig_takes, id >= 1 && id <= 15) << id;
    EXPECT_EQ(rig_takes, bridge_takes) << id;
  }
  EXPECT_EQ(error_of([&] { parse_rig(t.substr(0, t.size() - 1) + R"(, "tool_id": 16})", "rig.json"); }),
            "rig.json: tool_id: must be in 1..15 (got 16)");
}

TEST(Rig, JsonSyntaxErrorNamesLineAndColumn) {
  const std::string msg = error_of([] {
    parse_rig("{\n  \"format_version\": 1,\n  \"robot_uri\" \"x\"\n}\n", "rig.json");
  });
  // Line 3, column 17: the last character the parser read (the end of the stray "x").
  EXPECT_EQ(msg, "rig.json:3:17: JSON syntax error: syntax error while parsing object separator - "
                 "unexpected string literal; expected ':'");
}

TEST(Rig, EveryTruncationAndByteFlipOfTheExampleIsAConfigErrorOrAValidRig) {
  const std::string text = doc_examples("rig").at(0);
  int errors = 0;
  for (std::size_t n = 0; n < text.size(); ++n) {
    std::string cut = text.substr(0, n);
    std::string flipped = text;
    flipped[n] = static_cast<char>(flipped[n] ^ 0x5a);
    for (const std::string* t : {&cut, &flipped}) {
      try {
        parse_rig(*t, "rig.json");
      } catch (const ConfigError& e) {
        ++errors;
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);  // one line
      }
    }
  }
  EXPECT_GT(errors, static_cast<int>(text.size()));  // every truncation at least
}

TEST(Plan, BadGridsGiveOneLineWithTheNestedKey) {
  auto plan_error = [](const std::string& grid) {
    return error_of([&] {
      parse_plan(R"({"format_version": 1, "name": "p", "work_object": "pad", "grid": )" + grid +
                     "}",
                 "plan.json");
    });
  };
  EXPECT_EQ(plan_error(R"({"rows": 3, "columns": 3, "origin_mm": [0, 0], "pitch_mm": [1, 0]})"),
            "plan.json: grid.pitch_mm: must be > 0 mm along every axis with more than one point");
  EXPECT_EQ(plan_error(R"({"rows": 3, "columns": 3, "origin_mm": [0, 0], "pitch_mm": [1, 1],
                          "x_range_mm": [0, 2]})"),
            "plan.json: grid.x_range_mm: give either origin_mm + pitch_mm or x_range_mm + "
            "y_range_mm, not both");
  EXPECT_EQ(plan_error(R"({"rows": 3, "columns": 3, "x_range_mm": [5, 2], "y_range_mm": [0, 1]})"),
            "plan.json: grid.x_range_mm: must be [min, max] with min <= max");
  EXPECT_EQ(plan_error(R"({"rows": 0, "columns": 3, "x_range_mm": [0, 2], "y_range_mm": [0, 1]})"),
            "plan.json: grid.rows: must be in 1..1000 (got 0)");
  EXPECT_EQ(plan_error(R"({"rows": 2, "columns": 3, "x_range_mm": [0, 2]})"),
            "plan.json: grid.y_range_mm: missing (required)");
  EXPECT_EQ(plan_error(R"({"rows": 2, "columns": 3, "spacing_mm": 1})"),
            "plan.json: grid.spacing_mm: unknown key");
  const Plan one = parse_plan(R"({"format_version": 1, "name": "p", "work_object": "pad",
      "grid": {"rows": 1, "columns": 1, "x_range_mm": [4, 4], "y_range_mm": [7, 7]}})",
                              "plan.json");
  EXPECT_NEAR(one.point_m(0, 0).first, 4e-3, 1e-18);
  EXPECT_NEAR(one.point_m(0, 0).second, 7e-3, 1e-18);
}

}  // namespace
}  // namespace palp
