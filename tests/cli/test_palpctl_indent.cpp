// SPDX-License-Identifier: Apache-2.0
// palpctl indent against a real palp-sim: the result directory, the --json keys, the refusals
// that come before the device moves.
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
#include "palp/result.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class PalpctlIndent : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    dir_ = fs::temp_directory_path() /
           ("palpctl-indent-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProcessResult run(std::vector<std::string> args) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args);
  }

  // solid_1d, position 3, the floating tip just touching (the paper's start in contact)
  SimServer sim_{{"--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"}};
  fs::path dir_;
};

TEST_F(PalpctlIndent, JsonPrintsTheIssueKeysAndTheResultDirectoryReadsBack) {
  const std::string out = (dir_ / "solid-p3").string();
  const auto r = run({"indent", "--reps", "1", "--rate-Hz", "200", "--out-dir", out, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --json: no progress on stderr
  const json j = json::parse(r.out);
  for (const char* key : {"params", "contact_point_mm", "k_linear_N_per_mm", "r2_linear",
                          "E_star_hertz_Pa", "r2_hertz", "E_star_sneddon_Pa", "r2_sneddon",
                          "model_by_aic", "delta0_mm", "k_tangent_N_per_mm", "k_fd_N_per_mm",
                          "k_ls_window_N_per_mm", "k_fd_paper_N_per_mm", "k_at_depth_N_per_mm"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["delta0_mm"].get<double>(), 2.935, 0.2935);  // the paper's solid, within 10 %
  EXPECT_TRUE(j["delta0_mm_sd"].is_null());                   // one repetition
  EXPECT_EQ(j["delta0_mm_sd_reason"], "s.d. needs at least 2 repetitions with a value");
  EXPECT_EQ(j["run"]["end"], "completed");
  EXPECT_EQ(j["result_dir"], fs::absolute(out).lexically_normal().string());
  EXPECT_DOUBLE_EQ(j["params"]["kf_N_per_A"].get<double>(), 2.918);

  const palp::LoadedResult loaded = palp::load_result(out);
  EXPECT_EQ(loaded.summary["parameters"]["dwell_s"], 0.1);  // the 1d preset
  EXPECT_EQ(loaded.summary["parameters"]["rate_Hz"], 200);
  EXPECT_EQ(loaded.summary["device"]["serial"], "SIM-0001");
  EXPECT_EQ(loaded.summary["analysis"]["delta0_mm"], j["delta0_mm"]);
  ASSERT_EQ(loaded.recordings.size(), 1u);
  const palp::Recording& rec = loaded.recordings[0].second;
  EXPECT_TRUE(rec.p_Pa[5].has_value());  // the pressure columns: the pressure-force test
  ASSERT_TRUE(rec.sidecar);
  EXPECT_EQ(rec.sidecar->zeroing.at(0)["what"], "pressure_zero");  // zeroed before the ramp
  EXPECT_DOUBLE_EQ(rec.i_cmd_A->front(), 0.5);  // only the ramp's samples, from its first step

  // the saved recording re-analysed without the device gives the same numbers, key by key
  const auto a = palpctl({"--json", "analyze", "indentation", "--input",
                          (fs::path(out) / "indentation.csv").string()});
  ASSERT_EQ(a.code, 0) << a.err;
  const json b = json::parse(a.out);
  for (const auto& [key, value] : b.items()) {
    if (key == "params") continue;
    EXPECT_EQ(j.value(key, json("absent from indent --json")), value) << key;
  }
  // and so does the pressure-force test (every channel; solid_1d has none, so noise about zero)
  const auto pa = palpctl({"--json", "analyze", "pressure", "--input",
                           (fs::path(out) / "indentation.csv").string()});
  ASSERT_EQ(pa.code, 0) << pa.err;
  const json pj = json::parse(pa.out);
  EXPECT_EQ(j["pressure"]["channels"], pj["channels"]);
  EXPECT_EQ(loaded.summary["pressure"]["channels"], pj["channels"]);
}

TEST_F(PalpctlIndent, CtrlCMidRampExits130AndWritesTheResultOfWhatWasRecorded) {
  const std::string out = (dir_ / "cut").string();
  ASSERT_TRUE(sim_.wait_no_client());
  // paced at 20x real time, the 1d preset's 5 repetitions (~120 s of device time) take ~6 s, so
  // the SIGINT 1 s in lands mid-ramp however fast the simulation runs unpaced
  ASSERT_EQ(sim_.control("pace 20").rfind("ok", 0), 0u);
  const std::vector<std::string> args = {PALPCTL_BINARY, "--uri", sim_.uri(), "indent",
                                         "--rate-Hz", "200", "--out-dir", out};
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
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "palpctl died by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const palp::LoadedResult r = palp::load_result(out);
  EXPECT_EQ(r.summary["run"]["interrupted"], true);
  EXPECT_EQ(r.summary["run"]["end"], "interrupted");
  EXPECT_GT(r.summary["run"]["samples"].get<int>(), 0);
  EXPECT_LT(r.summary["run"]["repetitions_done"].get<int>(), 5);
}

TEST_F(PalpctlIndent, AnExistingOutDirIsRefusedBeforeTheDeviceMoves) {
  const std::string out = (dir_ / "taken").string();
  fs::create_directories(out);
  const auto r = run({"indent", "--out-dir", out});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(out + " already exists; choose another --out-dir, or pass --overwrite to "
                             "replace it"),
            std::string::npos)
      << r.err;
}

TEST_F(PalpctlIndent, AStreamRateAbove1kHzIsAUsageError) {
  const auto r = run({"indent", "--rate-Hz", "2000", "--out-dir", (dir_ / "x").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--rate-Hz"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
}

}  // namespace
}  // namespace palpctl::test
