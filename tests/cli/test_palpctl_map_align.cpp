// SPDX-License-Identifier: Apache-2.0
// palpctl map --align normal against palp-sim's 10-degree plane with its robot bridge: the
// options, a refused trace (exit 2 before anything moves), and a point indented along the
// normal of a local trace with the tilt it used printed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/trace.hpp"

// a named namespace: the test sources may build as one unity translation unit
namespace map_align_cli_test {

using palpctl::test::palpctl;
using palpctl::test::ProcessResult;
using palpctl::test::SimServer;
namespace fs = std::filesystem;


class PalpctlMapAlign : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    const unsigned rp = sim_.robot_port();
    ASSERT_NE(rp, 0u) << sim_.banner();
    dir_ = fs::temp_directory_path() /
           ("palpctl-map-align-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // the work object is palp-sim's phantom frame; the plane is 8.8 mm high at its highest
    std::ofstream(dir_ / "rig.json") << R"({"format_version": 1, "robot_uri": "modbus://127.0.0.1:)"
                                     << rp << R"(", "probe_uri": ")" << sim_.uri() << R"(",
        "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 12,
        "work_object": {"name": "phantom", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}})";
    std::ofstream(dir_ / "plan.json")
        << R"({"format_version": 1, "name": "one point", "work_object": "phantom",
        "grid": {"rows": 1, "columns": 1, "origin_mm": [30, 35], "pitch_mm": [10, 10]},
        "contact_E_star_Pa": 3.3e6})";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> map_args(const std::string& out) const {
    return {"map",
            "--rig",
            (dir_ / "rig.json").string(),
            "--plan",
            (dir_ / "plan.json").string(),
            "--out-dir",
            (dir_ / out).string(),
            "--reps",
            "1"};
  }
  ProcessResult run(std::vector<std::string> args, double timeout_s = 180) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args, timeout_s);
  }
  SimServer sim_{{"--phantom", "plane_tilted_10", "--robot-port", "0"}};
  fs::path dir_;
};

TEST_F(PalpctlMapAlign, HelpListsTheAlignmentOptionsAndTraceWithoutAlignNormalIsAUsageError) {
  const auto h = palpctl({"map", "--help"});
  ASSERT_EQ(h.code, 0) << h.err;
  for (const char* o : {"--align", "--trace", "--local-trace-mm", "--max-tilt-deg"})
    EXPECT_NE(h.out.find(o), std::string::npos) << o;
  std::ofstream(dir_ / "trace.json") << "{}";
  auto args = map_args("m");
  args.insert(args.end(), {"--trace", (dir_ / "trace.json").string()});
  const auto r = palpctl(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "--trace: gives the normals for --align normal, which is not set");
}

TEST_F(PalpctlMapAlign, ATraceOfAnotherGridExits2BeforeAnythingMovesAndWritesNoMap) {
  palp::TracedSurface t;  // a 2 x 2 trace for the 1 x 1 plan
  t.rows = t.columns = 2;
  t.work_object = palp::Pose{0.600, 0.0, 0.300, 0, 0, std::numbers::pi};
  t.complete = t.normals_from_grid = true;
  for (int k = 0; k < 4; ++k) {  // touched along the phantom's z (base -z) 10 mm apart
    palp::TracePoint p;
    p.row = k / 2 + 1, p.column = k % 2 + 1, p.ok = true;
    p.tcp_at_rest =
        palp::Pose{0.600 + 0.010 * p.column, -0.010 * p.row, 0.330, 0, 0, std::numbers::pi};
    p.stroke_at_rest_m = 0.030;
    t.points.push_back(p);
  }
  t.resume_index = 4;
  palp::save_trace(dir_ / "trace.json", t);
  auto args = map_args("m");
  args.insert(args.end(), {"--align", "normal", "--trace", (dir_ / "trace.json").string()});
  const auto r = run(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(
      r.err.find("the alignment's trace is a 2 x 2 grid, the plan 1 x 1: trace the plan to map"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m" / "map.json"));
}

TEST_F(PalpctlMapAlign, ALocalTraceIndentsAlongTheTenDegreeNormalAndReportsTheTilt) {
  auto args = map_args("m");
  args.insert(args.begin(), "--json");
  args.insert(args.end(), {"--align", "normal"});
  const auto r = run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["tilt_deg"][0][0].is_number()) << r.out;
  EXPECT_NEAR(j["tilt_deg"][0][0].get<double>(), 10.0, 0.3);
  EXPECT_TRUE(j["analysis"]["k_fd_N_per_mm"][0][0].is_number()) << r.out;
  std::ifstream in(dir_ / "m" / "map.json");
  const auto m = nlohmann::json::parse(in);
  const auto& p = m["points"][0];
  EXPECT_EQ(p["align"], "local trace");
  EXPECT_NEAR(p["tilt_deg"].get<double>(), 10.0, 0.3);
  ASSERT_EQ(p["tool_axis"].size(), 3u);
  EXPECT_NEAR(p["tool_axis"][0].get<double>(), -std::sin(10 * std::numbers::pi / 180), 0.005);
}

}  // namespace map_align_cli_test
