// SPDX-License-Identifier: Apache-2.0
// palpctl map --dynamic against a real palp-sim (pad_2d, robot bridge): the dynamic grids printed
// and in --json, each point's identification directory, palpctl analyze map re-analysing them
// from the map directory and from its HDF5 export to the same numbers, the report's dynamic
// heat maps; the dynamic settings without --dynamic refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;


class PalpctlMapDynamic : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    const unsigned rp = sim_.robot_port();
    ASSERT_NE(rp, 0u) << sim_.banner();
    dir_ = fs::temp_directory_path() / ("palpctl-map-dynamic-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // the work object is palp-sim's phantom frame; columns 4 and 5 of the pad's grid (5: soft)
    std::ofstream(dir_ / "rig.json") << R"({"format_version": 1, "robot_uri": "modbus://127.0.0.1:)"
                                     << rp << R"(", "probe_uri": ")" << sim_.uri() << R"(",
        "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 8,
        "work_object": {"name": "pad", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}})";
    std::ofstream(dir_ / "plan.json")
        << R"({"format_version": 1, "name": "pad 1 x 2", "work_object": "pad",
        "grid": {"rows": 1, "columns": 2, "origin_mm": [40, 45], "pitch_mm": [10, 10]},
        "contact_E_star_Pa": 3.3e6})";
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProcessResult run(std::vector<std::string> args, double timeout_s = 120) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args, timeout_s);
  }
  std::vector<std::string> map_args(const fs::path& out) const {
    return {"map",
            "--rig",
            (dir_ / "rig.json").string(),
            "--plan",
            (dir_ / "plan.json").string(),
            "--out-dir",
            out.string(),
            "--reps",
            "1"};
  }
  SimServer sim_{{"--phantom", "pad_2d", "--robot-port", "0"}};
  fs::path dir_;
};

TEST_F(PalpctlMapDynamic,
       MapDynamicWritesEachPointsIdentificationAndAnalyzeMapGivesTheSameGridsAgain) {
  const fs::path out = dir_ / "m";
  std::vector<std::string> args = map_args(out);
  args.insert(args.begin(), "--json");
  args.push_back("--dynamic");
  const ProcessResult r = run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  const json& d = j["analysis"]["dynamic"];
  ASSERT_TRUE(d.is_object()) << r.out;
  EXPECT_EQ(d["points_identified"], 2);
  // the soft column (5) resonates lower than its stiff neighbour (4)
  EXPECT_LT(d["omega_n_rad_per_s"][0][1].get<double>(),
            0.9 * d["omega_n_rad_per_s"][0][0].get<double>());
  for (const char* p : {"r1_c1_dynamic", "r1_c2_dynamic"}) {
    EXPECT_TRUE(fs::exists(out / "points" / p / "result.json")) << p;
    EXPECT_TRUE(fs::exists(out / "points" / p / "sweep.csv")) << p;
  }
  const ProcessResult again = run({"--json", "analyze", "map", "--input", out.string()});
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(json::parse(again.out)["analysis"]["dynamic"], d);
#ifdef PALP_HAVE_HDF5
  const fs::path h5 = dir_ / "m.h5";
  const ProcessResult exported =
      run({"export", "--format", "hdf5", "--input", out.string(), "--out", h5.string()});
  ASSERT_EQ(exported.code, 0) << exported.err;
  const ProcessResult from_h5 = run({"--json", "analyze", "map", "--input", h5.string()});
  ASSERT_EQ(from_h5.code, 0) << from_h5.err;
  EXPECT_EQ(json::parse(from_h5.out)["analysis"]["dynamic"], d);
#endif
  const fs::path page = dir_ / "m.html";
  const ProcessResult report = run({"report", out.string(), "--out", page.string()});
  ASSERT_EQ(report.code, 0) << report.err;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* id :
       {"map-dynamic-omega_n_rad_per_s", "map-dynamic-zeta", "map-dynamic-E_loss_Pa"})
    EXPECT_NE(html.find(id), std::string::npos) << id;
}

TEST_F(PalpctlMapDynamic, DynamicSettingsWithoutDynamicAreRefusedNamingTheFlag) {
  std::vector<std::string> args = map_args(dir_ / "refused");
  args.insert(args.end(), {"--dynamic-amplitude-A", "0.05"});
  const ProcessResult r = run(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--dynamic-amplitude-A and --dynamic-measured-periods need --dynamic"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "refused"));
}

}  // namespace
}  // namespace palpctl::test
