// SPDX-License-Identifier: Apache-2.0
// palpctl's exit paths against a real palp-sim (issue 17, items 2, 4 and 9): a lost reply during
// indent leaves no program, 0 A and no latched fault; --overwrite and a map's point directories
// never delete a file palp did not write; with the fault latch set run, indent and map all exit
// 6; a map whose palpctl was killed (kill -9) mid-point resumes to the end with --resume.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/probe.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path fresh_dir(const char* what) {
  const fs::path d = fs::temp_directory_path() /
                     (std::string("palpctl-") + what + "-" + std::to_string(::getpid()) + "-" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& f) {
  std::ifstream in(f);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// ---- indent, the probe alone -------------------------------------------------------------------

class PalpctlExitIndent : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    dir_ = fresh_dir("exit");
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProcessResult run(std::vector<std::string> args) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args);
  }
  SimServer sim_{{"--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"}};
  fs::path dir_;
};

TEST_F(PalpctlExitIndent, ALostReplyDuringIndentLeavesNoProgramZeroCurrentAndNoLatchedFault) {
  // every 5th / 7th device frame lost: replies, events and sample batches alike
  for (const char* every : {"5", "7"}) {
    ASSERT_EQ(sim_.control(std::string("drop-frames ") + every), "ok\n");
    const auto r = run({"indent", "--reps", "1", "--rate-Hz", "200", "--out-dir",
                        (dir_ / every).string(), "--json"});
    EXPECT_TRUE(r.code == 0 || r.code == 4) << every << ": exit " << r.code << ": " << r.err;
    ASSERT_EQ(sim_.control("drop-frames 0"), "ok\n");
    ASSERT_TRUE(sim_.wait_no_client());
    std::this_thread::sleep_for(800ms);  // past the 0.5 s heartbeat timeout: a hold left on trips it
    palp::Probe probe(sim_.uri());
    const palp::Status st = probe.status();
    EXPECT_EQ(st.fault, palp::proto::FaultReason::none) << every << ": " << r.err;
    EXPECT_EQ(st.i_cmd_A, 0.0) << every;
    EXPECT_NE(st.program_state, palp::proto::ProgramState::running) << every;
    EXPECT_FALSE(st.streaming) << every;
  }
}

TEST_F(PalpctlExitIndent, OverwriteRefusesADirectoryPalpNeverWroteNamesItAndKeepsTheFile) {
  const fs::path mine = dir_ / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "the user's notes";
  const auto r = run({"indent", "--out-dir", mine.string(), "--overwrite"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(mine.string() + " is not a result directory palp wrote"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(mine / "notes.txt"), "the user's notes");
}

// ---- with the robot: map, and the fault latch ----------------------------------------------------


class PalpctlExitMap : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    const unsigned rp = sim_.robot_port();
    ASSERT_NE(rp, 0u) << sim_.banner();
    dir_ = fresh_dir("exit-map");
    // the work object is palp-sim's phantom frame: (600, 0, 300) mm, C = 180 deg
    std::ofstream(dir_ / "rig.json") << R"({"format_version": 1, "robot_uri": "modbus://127.0.0.1:)" << rp
                                     << R"(", "probe_uri": ")" << sim_.uri() << R"(",
        "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 8,
        "work_object": {"name": "pad", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}})";
    std::ofstream(dir_ / "plan.json") << R"({"format_version": 1, "name": "pad 1 x 3", "work_object": "pad",
        "grid": {"rows": 1, "columns": 3, "origin_mm": [10, 45], "pitch_mm": [40, 40]},
        "contact_E_star_Pa": 3.3e6})";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> map_args(const fs::path& out) const {
    return {"map", "--rig", (dir_ / "rig.json").string(), "--plan", (dir_ / "plan.json").string(),
            "--out-dir", out.string(), "--reps", "1"};
  }
  ProcessResult run(std::vector<std::string> args, double timeout_s = 120) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args, timeout_s);
  }
  SimServer sim_{{"--phantom", "pad_2d", "--robot-port", "0"}};
  fs::path dir_;
};

TEST_F(PalpctlExitMap, WithTheFaultLatchSetRunIndentAndMapEachExit6NamingTheFaultAndHowToResume) {
  {  // travel_limit: a 1 mm travel window about the resting coil, then 1 A
    palp::Probe probe(sim_.uri());
    auto p = probe.params();
    const std::int32_t c = probe.status().encoder_counts;
    p.travel_min_counts = c - 500;
    p.travel_max_counts = c + 500;
    probe.set_params(p);
    palp::HoldProgram h;
    h.current_A = 1.0f;
    h.duration_s = 2.0f;
    EXPECT_THROW(probe.run(h, 10s), palp::FaultError);
    ASSERT_EQ(probe.status().fault, palp::proto::FaultReason::travel_limit);
  }
  const auto r = run({"run", "hold", "--current-A", "0.2", "--seconds", "0.1", "--out",
                      (dir_ / "h.csv").string()});
  EXPECT_EQ(r.code, 6) << r.err;
  EXPECT_NE(r.err.find("travel_limit"), std::string::npos) << r.err;
  const auto i = run({"indent", "--out-dir", (dir_ / "i").string()});
  EXPECT_EQ(i.code, 6) << i.err;
  EXPECT_NE(i.err.find("travel_limit"), std::string::npos) << i.err;
  const auto m = run(map_args(dir_ / "m"));
  EXPECT_EQ(m.code, 6) << m.err;
  EXPECT_NE(m.err.find("travel_limit"), std::string::npos) << m.err;
  // the hint to resume carries the options a resumed map insists on
  std::vector<std::string> args = map_args(dir_ / "a");
  for (const char* extra : {"--adaptive", "--max-points", "3", "--max-force-N", "3.5"})
    args.push_back(extra);
  const auto a = run(args);
  EXPECT_EQ(a.code, 6) << a.err;
  EXPECT_NE(a.err.find("resume with: palpctl map --rig " + (dir_ / "rig.json").string() + " --plan " +
                       (dir_ / "plan.json").string() + " --out-dir " + (dir_ / "a").string() +
                       " --reps 1 --adaptive --max-points 3 --max-force-N 3.5 --resume\n"),
            std::string::npos)
      << a.err;
}

TEST_F(PalpctlExitMap, MapRefusesAPointDirectoryPalpDidNotWriteNamesItAndKeepsIt) {
  const fs::path out = dir_ / "m";
  fs::create_directories(out / "points" / "r1_c1");
  std::ofstream(out / "points" / "r1_c1" / "notes.txt") << "the user's notes";
  const auto r = run(map_args(out));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find((out / "points" / "r1_c1").string() + " is not a result directory palp wrote"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(out / "points" / "r1_c1" / "notes.txt"), "the user's notes");
  EXPECT_FALSE(fs::exists(out / "map.json"));
}

TEST_F(PalpctlExitMap, AnAdaptiveBudgetBelowTheCoarseDesignIsRefusedBeforeAnythingMoves) {
  std::vector<std::string> args = map_args(dir_ / "m");
  args.insert(args.end(), {"--adaptive", "--max-points", "2"});
  const auto r = run(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "palpctl: adaptive grid: the coarse design's 3 points exceed the budget of 2 (raise "
            "max_points)");
  EXPECT_FALSE(fs::exists(dir_ / "m" / "map.json"));
}

// depth sensitivity (docs/depth-sensitivity.md): a force beyond palp-sim's 3.2 A current clamp
TEST_F(PalpctlExitMap, MapMaxForceBeyondTheCurrentClampExits2NamingTheNumbersBeforeMoving) {
  const fs::path out = dir_ / "m";
  std::vector<std::string> args = map_args(out);
  args.insert(args.end(), {"--max-force-N", "9"});
  const auto r = run(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("max_force_N 9 N needs up to 3.660 A at the ramp's top (I_c 0.5 A + (9 N + "
                       "k_v 43.9 N/m x 5 mm displacement limit) / K_f 2.918 N/A), above the "
                       "coil's current clamp 3.2 A: at most 7.65 N"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out / "map.json"));
}

TEST_F(PalpctlExitMap, AMapKilledMidPointResumesToTheEndWithoutAManualStep) {
  const fs::path out = dir_ / "m";
  std::vector<std::string> args = map_args(out);
  args.insert(args.begin(), {PALPCTL_BINARY, "--uri", sim_.uri()});
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  // kill -9 as soon as the first point is in map.json: the second is under way (a point takes
  // about 0.2 s of wall time at palp-sim's fast pace)
  int kept = 0;
  for (int k = 0; k < 30000 && kept < 1; ++k) {
    std::this_thread::sleep_for(1ms);
    std::error_code ec;
    if (!fs::exists(out / "map.json", ec)) continue;
    try {
      kept = json::parse(slurp(out / "map.json")).value("resume_index", 0);
    } catch (const std::exception&) {
    }
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_GE(kept, 1) << "map.json never showed the first point";
  const json partial = json::parse(slurp(out / "map.json"));
  ASSERT_FALSE(partial.value("complete", true)) << "the map ended before the kill";
  ASSERT_LT(partial.value("resume_index", 0), 3);

  ASSERT_TRUE(sim_.wait_no_client());
  std::vector<std::string> resume = map_args(out);
  resume.push_back("--resume");
  resume.push_back("--json");
  const auto r = run(resume, 240);
  ASSERT_EQ(r.code, 0) << r.err;
  const json m = json::parse(slurp(out / "map.json"));
  EXPECT_TRUE(m.value("complete", false));
  ASSERT_EQ(m["points"].size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(m["points"][k]["column"], k + 1);
    EXPECT_TRUE(m["points"][k]["indented"].get<bool>()) << k;
  }
  EXPECT_TRUE(fs::exists(out / "points" / "r1_c3" / "result.json"));
}

}  // namespace
}  // namespace palpctl::test
