// SPDX-License-Identifier: Apache-2.0
// palpctl trace against palp-sim with its robot bridge: Ctrl-C (a real SIGINT) mid-plan leaves
// the arm at the safe height and a partial trace.json; --resume finishes it without repeats.
#include <gtest/gtest.h>

#include <fcntl.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"

namespace {

using palpctl::test::palpctl;
using palpctl::test::SimServer;
namespace fs = std::filesystem;


double status_value(const std::string& status, const std::string& key) {
  const auto at = status.find(" " + key + "=");
  return at == std::string::npos ? -1e9 : std::stod(status.substr(at + key.size() + 2));
}

nlohmann::json read_json(const fs::path& f) {
  std::ifstream in(f);
  return nlohmann::json::parse(in);
}

TEST(PalpctlTrace, CtrlCMidPlanExits130AtTheSafeHeightAndResumeFinishesWithoutRepeats) {
  SimServer sim({"--phantom", "pad_2d", "--robot-port", "0"});
  ASSERT_TRUE(sim.ok()) << sim.banner();
  const unsigned rp = sim.robot_port();
  ASSERT_NE(rp, 0u) << sim.banner();
  const fs::path dir = fs::temp_directory_path() / ("palpctl_trace_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // the work object is palp-sim's phantom frame: (600, 0, 300) mm, C = 180 deg
  std::ofstream(dir / "rig.json") << R"({"format_version": 1, "robot_uri": "modbus://127.0.0.1:)" << rp
                                  << R"(", "probe_uri": ")" << sim.uri() << R"(",
      "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 8,
      "work_object": {"name": "pad", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}})";
  std::ofstream(dir / "plan.json") << R"({"format_version": 1, "name": "pad 3 x 3", "work_object": "pad",
      "grid": {"rows": 3, "columns": 3, "origin_mm": [10, 5], "pitch_mm": [40, 40]},
      "contact_E_star_Pa": 3.3e6})";
  const std::vector<std::string> args = {PALPCTL_BINARY, "trace", "--rig", (dir / "rig.json").string(),
                                         "--plan", (dir / "plan.json").string(), "--out-dir",
                                         (dir / "out").string()};
  // run it, and press Ctrl-C once trace.json shows two finished points
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
  const fs::path file = dir / "out" / "trace.json";
  bool seen = false;
  for (int k = 0; k < 3000 && !seen; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::error_code ec;
    if (!fs::exists(file, ec)) continue;
    try {
      seen = read_json(file).value("resume_index", 0) >= 2;
    } catch (const std::exception&) {
    }
  }
  ASSERT_TRUE(seen) << "trace.json never showed two points";
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "palpctl died by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const auto partial = read_json(file);
  EXPECT_FALSE(partial.value("complete", true));
  EXPECT_EQ(partial.value("stopped_because", std::string{}), "cancelled");
  const int kept = partial.value("resume_index", 0);
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 9);
  // the TCP (tip at stroke origin) at least safe height + the whole stroke above the datum
  EXPECT_GE(status_value(sim.control("status"), "robot_z_mm"), 300.0 + 8.0 + 34.0 - 1e-3);

  ASSERT_TRUE(sim.wait_no_client());
  std::vector<std::string> resume(args.begin() + 1, args.end());
  resume.push_back("--resume");
  resume.push_back("--json");
  const auto r = palpctl(resume, 120);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto whole = read_json(file);
  EXPECT_TRUE(whole.value("complete", false));
  ASSERT_EQ(whole["points"].size(), 9u);
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(whole["points"][static_cast<std::size_t>(k)]["row"], k / 3 + 1);
    EXPECT_EQ(whole["points"][static_cast<std::size_t>(k)]["column"], k % 3 + 1);
    EXPECT_TRUE(whole["points"][static_cast<std::size_t>(k)]["ok"].get<bool>());
  }
  for (int k = 0; k < kept; ++k)  // the points traced before Ctrl-C are kept as they were
    for (std::size_t i = 0; i < 6; ++i)  // (to the rounding of the mm <-> m conversions)
      EXPECT_NEAR(whole["points"][static_cast<std::size_t>(k)]["tcp_at_rest_mm_deg"][i].get<double>(),
                  partial["points"][static_cast<std::size_t>(k)]["tcp_at_rest_mm_deg"][i].get<double>(), 1e-9);
  fs::remove_all(dir);
}

}  // namespace
