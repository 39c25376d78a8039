// SPDX-License-Identifier: Apache-2.0
// The host-loss watchdog: a host process holding current is killed (SIGKILL, no goodbye), and
// the device must bring the coil to 0 A by itself within its heartbeat timeout. The doomed host
// is this executable re-run with kHostLossChildFlag; it speaks the public SDK only, as every
// scenario does. What the scenario proves is in README.md.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <thread>

#include "bench.hpp"

namespace palp::hil {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// The doomed host: connects (retrying a refused connection for 2 s, as the fixture does), sets
// the heartbeat timeout, starts a hold that lasts until stopped, and prints one line per sighting
// until it is killed:
//   holding elapsed_us=<program time> state=<program state> i_A=<measured> fault=<latched>
// Any SDK error ends it with "error <what>" on stdout and exit code 1.
int host_loss_child(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s %s URI HEARTBEAT_TIMEOUT_MS CURRENT_A\n", argv[0],
                 kHostLossChildFlag);
    return 2;
  }
  try {
    std::unique_ptr<Probe> probe;
    const auto give_up = Clock::now() + 2s;
    while (!probe) {
      try {
        probe = std::make_unique<Probe>(argv[2]);
      } catch (const ConnectionError&) {
        if (Clock::now() > give_up) throw;
        std::this_thread::sleep_for(20ms);
      }
    }
    Params p = probe->params();
    p.heartbeat_timeout_ms = static_cast<std::uint32_t>(std::atoi(argv[3]));
    probe->set_params(p);
    HoldProgram h;
    h.current_A = static_cast<float>(std::atof(argv[4]));
    h.duration_s = 0.0f;  // until stopped: only the watchdog ends it
    probe->load(h);
    probe->start();
    while (true) {
      const proto::ProgramStatus ps = probe->program_status();
      const Status st = probe->status();
      std::printf("holding elapsed_us=%llu state=%s i_A=%.5f fault=%s\n",
                  static_cast<unsigned long long>(ps.elapsed_us), proto::enum_name(ps.state),
                  st.i_A, proto::enum_name(st.fault));
      std::fflush(stdout);
      std::this_thread::sleep_for(20ms);
    }
  } catch (const Error& e) {
    std::printf("error %s\n", e.what());
    return 1;
  }
}

namespace {

std::map<std::string, std::string> fields(const std::string& line) {
  std::map<std::string, std::string> f;
  std::istringstream in(line);
  std::string w;
  while (in >> w)
    if (const auto eq = w.find('='); eq != std::string::npos) f[w.substr(0, eq)] = w.substr(eq + 1);
  return f;
}

std::string self_executable() {
  char path[4096];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  return n > 0 ? std::string(path, static_cast<std::size_t>(n)) : std::string();
}

constexpr std::uint32_t kTimeout_ms = 300;  // the doomed host's heartbeat timeout
constexpr double kHold_A = 0.3;
// The scenario looks at the device once, this long after the kill: the watchdog's timeout, then
// 500 ms for the coil's current to decay (palp-sim's coil: below 1 mA 0.13 s after 0 V) and for
// a loaded machine's scheduling (the QEMU board's watchdog clock leaves out a stall of QEMU
// beyond 0.1 s: firmware/board/qemu/qemu_board.hpp). A look any earlier would feed the watchdog
// it tests. That the hold ended within the timeout is judged in device time below.
constexpr auto kLookAfterKill = std::chrono::milliseconds(kTimeout_ms + 500);
// ... and the connection that looks may take this long on a loaded machine (a handshake and a
// few requests; QEMU's UART carries them in a few ms).
constexpr auto kConnectAllowance = 1000ms;
// On hardware the hold ends at least the timeout after the last sighting (that sighting's
// request fed the watchdog) and at most this much later: the time between the sighting and the
// kill (one status round trip, the pipe, scheduling) and a tick. The hold's end is read from the
// program's elapsed time, counted in control ticks, while the watchdog counts the board's clock:
// the lower bound needs the two to agree (measured: the device clock within kSamePace of the
// host's; QEMU without -icount loses ticks that the host does not schedule in time), the upper
// bound holds whenever ticks are not faster than real time (palp-sim's run at its pace).
constexpr double kTripLateness_s = 0.15;
constexpr double kSamePace = 0.02;

/// Device seconds per host second, from two Status replies 0.5 s apart (each stamped at the
/// middle of its round trip).
double device_clock_rate(Probe& probe) {
  const auto stamp = [&](double& host_s) {
    const auto t0 = Clock::now();
    const double device_s = probe.status().t_device_s;
    host_s = std::chrono::duration<double>(t0.time_since_epoch() + (Clock::now() - t0) / 2).count();
    return device_s;
  };
  double h0 = 0, h1 = 0;
  const double d0 = stamp(h0);
  std::this_thread::sleep_for(500ms);
  const double d1 = stamp(h1);
  return (d1 - d0) / (h1 - h0);
}

using HostLoss = Scenario;
TEST_F(HostLoss, AKilledHostsHoldEndsInHeartbeatTimeoutWithTheCoilAt0AWithinTheTimeout) {
  const std::string uri = Bench::get().uri();
  const bool simulated = probe().info().has(proto::Capability::simulated);
  const double clock_rate = device_clock_rate(probe());
  disconnect();  // the device serves the doomed host now
  Child host({self_executable(), kHostLossChildFlag, uri, std::to_string(kTimeout_ms),
              std::to_string(kHold_A)});
  ASSERT_TRUE(host.running()) << host.error();

  // the hold is running and kept alive by the host's heartbeat for twice the timeout
  std::string line;
  Clock::time_point first{};
  std::map<std::string, std::string> last;
  int sightings = 0;
  while (first == Clock::time_point{} ||
         Clock::now() - first < 2 * std::chrono::milliseconds(kTimeout_ms)) {
    ASSERT_TRUE(host.read_line(line, 10s))
        << "the host printed nothing for 10 s; its stderr: " << host.stderr_text();
    ASSERT_EQ(line.rfind("holding ", 0), 0u) << line << host.stderr_text();
    last = fields(line);
    ASSERT_EQ(last["state"], "running") << line;
    ASSERT_EQ(last["fault"], "none") << line;
    if (first == Clock::time_point{}) first = Clock::now();
    ++sightings;
  }
  EXPECT_NEAR(std::atof(last["i_A"].c_str()), kHold_A, 0.1 * kHold_A)
      << "the coil carries the hold";
  // the newest sighting (a fresh one, and whatever else is already in the pipe), then at once:
  ASSERT_TRUE(host.read_line(line, 5s)) << host.stderr_text();
  while (host.read_line(line, 0ms)) {
  }
  last = fields(line);
  host.signal(SIGKILL);
  const auto killed = Clock::now();
  ASSERT_EQ(last["state"], "running") << line;
  const double sighted_elapsed_s = std::atof(last["elapsed_us"].c_str()) * 1e-6;
  while (!host.exited()) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(WIFSIGNALED(host.exit_status()) && WTERMSIG(host.exit_status()) == SIGKILL);

  std::this_thread::sleep_for(kLookAfterKill - (Clock::now() - killed));
  connect();
  const Status st = probe().status();
  const double looked_s = std::chrono::duration<double>(Clock::now() - killed).count();
  EXPECT_EQ(st.fault, proto::FaultReason::heartbeat_timeout) << probe().fault().text;
  EXPECT_EQ(st.state, proto::DeviceState::faulted);
  EXPECT_EQ(st.i_cmd_A, 0.0) << "a fault commands 0 A";
  double sum_A = 0;  // the measured current, ten looks (2 mA rms of noise on palp-sim)
  for (int k = 0; k < 10; ++k) sum_A += probe().status().i_A;
  EXPECT_LT(std::fabs(sum_A / 10), 0.005) << "the measured coil current, mean of 10 Status";
  const proto::ProgramStatus ps = probe().program_status();
  EXPECT_EQ(ps.kind, proto::ProgramKind::hold);
  EXPECT_EQ(ps.state, proto::ProgramState::finished) << "no program running";
  EXPECT_EQ(ps.end, proto::ProgramEnd::fault);
  EXPECT_LE(looked_s, std::chrono::duration<double>(kLookAfterKill + kConnectAllowance).count());
  // device time from the last sighting to the hold's end (its elapsed time stops at the end)
  const double trip_after_sighting_s =
      static_cast<double>(ps.elapsed_us) * 1e-6 - sighted_elapsed_s;
  std::printf(
      "[  FIGURES ] %d sightings of the %.1f A hold; killed; the device seen at 0 A, "
      "faulted heartbeat_timeout, %.3f s after the kill (the timeout is %.3f s); the hold "
      "ended %.3f s of device time after the last sighting; the device clock ran %.3f s "
      "per host s%s\n",
      sightings, kHold_A, looked_s, kTimeout_ms * 1e-3, trip_after_sighting_s, clock_rate,
      simulated ? " (palp-sim: its program clock runs at its pace)" : "");
  if (!simulated) {
    EXPECT_LE(trip_after_sighting_s, kTimeout_ms * 1e-3 + kTripLateness_s);
    if (std::fabs(clock_rate - 1.0) < kSamePace) {
      EXPECT_GE(trip_after_sighting_s, kTimeout_ms * 1e-3 - 1e-4);
    }
  }

  probe().clear_fault();
  const Status after = probe().status();
  EXPECT_EQ(after.fault, proto::FaultReason::none);
  EXPECT_EQ(after.state, proto::DeviceState::idle);
}

}  // namespace
}  // namespace palp::hil
