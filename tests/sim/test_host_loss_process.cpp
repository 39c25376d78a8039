// SPDX-License-Identifier: Apache-2.0
// Host loss end to end (issue 17, item 1): a real palp-sim process at real time, a real
// `palpctl run hold --current-A 1 --seconds 30` process, killed (SIGKILL) or stopped (SIGSTOP)
// after about a second; nobody reconnects. palp-sim's control `status` is polled until the
// coil's true current is 0 and heartbeat_timeout is latched: that must come within the
// heartbeat timeout (500 ms) plus a margin of wall time (the polls' 20 ms, a step, scheduling
// on a loaded machine). It froze before: no client, no virtual time, no watchdog. The next host
// is then refused `faulted` (heartbeat_timeout), not `busy`, and the next palpctl says so.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include "sim_process.hpp"

namespace palp::sim {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

std::map<std::string, std::string> fields(const std::string& status) {
  std::map<std::string, std::string> f;
  std::istringstream in(status);
  std::string w;
  while (in >> w)
    if (const auto eq = w.find('='); eq != std::string::npos) f[w.substr(0, eq)] = w.substr(eq + 1);
  return f;
}

/// palpctl with these arguments, its output thrown away; returns its pid.
pid_t spawn_palpctl(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    std::vector<std::string> a = {PALPCTL_BINARY};
    a.insert(a.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& s : a) argv.push_back(s.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  return pid;
}

struct Loss {
  bool held = false;        // the 1 A hold was running before the host was lost
  double to_fault_s = -1;   // wall time from the loss to heartbeat_timeout latched
  double to_zero_s = -1;    // ... and to the coil's true current below 1 mA (it decays with L/R)
};

/// Starts the hold, loses the host with `signal` after ~1 s, polls until safe (or 5 s).
Loss lose_host(test::SimProcess& sim, int signal, pid_t& pid) {
  Loss r;
  const std::string dir = ::testing::TempDir();
  pid = spawn_palpctl({"--uri", sim.uri(), "run", "hold", "--current-A", "1", "--seconds", "30",
                       "--out", dir + "host_loss_" + std::to_string(::getpid()) + ".csv",
                       "--overwrite"});
  const auto start = Clock::now();
  while (Clock::now() - start < 10s) {  // the hold runs (connect, zero, stream, start)
    auto f = fields(sim.control("status"));
    if (f["client"] == "1" && std::atof(f["coil_A"].c_str()) > 0.9) {
      r.held = true;
      break;
    }
    std::this_thread::sleep_for(20ms);
  }
  if (!r.held) return r;
  std::this_thread::sleep_for(1s);
  ::kill(pid, signal);
  const auto lost = Clock::now();
  while (Clock::now() - lost < 5s) {
    auto f = fields(sim.control("status"));
    const double t = std::chrono::duration<double>(Clock::now() - lost).count();
    if (f["fault"] == "heartbeat_timeout" && r.to_fault_s < 0) r.to_fault_s = t;
    if (r.to_fault_s >= 0 && std::abs(std::atof(f["coil_A"].c_str())) < 1e-3) {
      r.to_zero_s = t;
      break;
    }
    std::this_thread::sleep_for(5ms);
  }
  return r;
}

constexpr double kHeartbeatTimeout_s = 0.5;  // SPEC default, what palpctl leaves in force
constexpr double kMargin_s = 0.2;
constexpr double kDecay_s = 0.2;  // the plant's coil current after 0 V: < 1 mA in about 0.13 s

/// palp-sim at real time, a palpctl hold killed with SIGKILL (reaped) after about a second.
Loss killed_hold(test::SimProcess& sim) {
  if (!sim.ok() || sim.control("pace realtime") != "ok") return {};
  pid_t pid = -1;
  const Loss r = lose_host(sim, SIGKILL, pid);
  ::waitpid(pid, nullptr, 0);
  return r;
}

TEST(HostLossProcess, AKilledPalpctlsHoldIsAtZeroAmpsWithinTheHeartbeatTimeoutWithNoReconnect) {
  test::SimProcess sim({}, false);
  const Loss r = killed_hold(sim);
  ASSERT_TRUE(r.held) << sim.banner();
  EXPECT_GE(r.to_zero_s, 0.0) << "still not at 0 A 5 s after the host died";
  EXPECT_LT(r.to_zero_s, kHeartbeatTimeout_s + kMargin_s + kDecay_s);
  EXPECT_LT(r.to_fault_s, kHeartbeatTimeout_s + kMargin_s);
  std::printf("kill -9 -> heartbeat_timeout %.3f s, < 1 mA %.3f s\n", r.to_fault_s, r.to_zero_s);
  // the next host is refused for the latched fault (not told the device is busy with the hold)
  ASSERT_TRUE(sim.connect_device_now());
  sim.send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "test"}, 1);
  proto::DeviceInfo info;
  ASSERT_TRUE(sim.await(1, info));
  sim.send(proto::ProgramStart{}, 2);
  proto::Nak nak;
  ASSERT_TRUE(sim.await(2, nak));
  EXPECT_EQ(nak.error, proto::ErrorCode::faulted);
  EXPECT_EQ(nak.detail, static_cast<std::int32_t>(proto::FaultReason::heartbeat_timeout));
}

TEST(HostLossProcess, TheNextPalpctlAfterAKilledOneIsToldTheLatchedFaultNotBusy) {
  test::SimProcess sim({}, false);
  const Loss r = killed_hold(sim);
  ASSERT_TRUE(r.held) << sim.banner();
  ASSERT_GE(r.to_fault_s, 0.0);
  // the dead host's stream is still running: the next palpctl stops it on connecting, and its
  // hold is refused for the latched fault (exit 6), not `StreamConfigure refused: busy`
  const std::string cmd = std::string(PALPCTL_BINARY) + " --uri " + sim.uri() +
                          " run hold --current-A 0.5 --seconds 1 --out " + ::testing::TempDir() +
                          "host_loss_next_" + std::to_string(::getpid()) + ".csv --overwrite 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = ::pclose(p);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 6) << out;
  EXPECT_NE(out.find("heartbeat_timeout"), std::string::npos) << out;
  EXPECT_EQ(out.find("busy"), std::string::npos) << out;
  EXPECT_LT(std::abs(std::atof(fields(sim.control("status"))["coil_A"].c_str())), 1e-3);
}

TEST(HostLossProcess, AStoppedPalpctlsHoldIsAtZeroAmpsWithinTheHeartbeatTimeout) {
  test::SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_EQ(sim.control("pace realtime"), "ok");
  pid_t pid = -1;
  const Loss r = lose_host(sim, SIGSTOP, pid);
  ::kill(pid, SIGKILL);  // (SIGKILL ends a stopped process too)
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(r.held);
  EXPECT_GE(r.to_zero_s, 0.0) << "still not at 0 A 5 s after the host stopped";
  EXPECT_LT(r.to_zero_s, kHeartbeatTimeout_s + kMargin_s + kDecay_s);
  EXPECT_LT(r.to_fault_s, kHeartbeatTimeout_s + kMargin_s);
  std::printf("SIGSTOP -> heartbeat_timeout %.3f s, < 1 mA %.3f s\n", r.to_fault_s, r.to_zero_s);
}

}  // namespace
}  // namespace palp::sim
