// SPDX-License-Identifier: Apache-2.0
// tcp:// and serial:// against a real palp-sim process: tcp://HOST:PORT is the simulator's
// device socket under the name a user expects; serial:// is reached through a pseudo-terminal
// whose master a relay thread joins to that socket byte for byte, as a UART-attached board's
// USB-serial adapter would (a pty ignores the baud; the SDK still budgets the stream by it).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>

#include "../unit/pty_pair.hpp"
#include "palp/probe.hpp"
#include "sim_process.hpp"

namespace {

using namespace std::chrono_literals;
using palp::sim::test::SimProcess;
using palp::test::PtyPair;
using testing::HasSubstr;
using Clock = std::chrono::steady_clock;

/// Copies bytes both ways between a pty's master and palp-sim's device socket until stopped.
class PtyRelay {
 public:
  PtyRelay(int master, std::uint16_t device_port)
      : master_(master), sock_(palp::sim::test::connect_loopback(device_port)) {
    if (sock_ >= 0) thread_ = std::thread([this] { run(); });
  }
  ~PtyRelay() {
    stop();
    if (sock_ >= 0) ::close(sock_);
  }
  bool ok() const { return sock_ >= 0; }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run() {
    pollfd p[2] = {{master_, POLLIN, 0}, {sock_, POLLIN, 0}};
    while (!stop_) {
      if (::poll(p, 2, 20) <= 0) continue;
      if (p[0].revents != 0 && !copy(master_, sock_)) return;
      if (p[1].revents != 0 && !copy(sock_, master_)) return;
    }
  }
  static bool copy(int from, int to) {
    std::uint8_t b[4096];
    const ssize_t n = ::read(from, b, sizeof b);
    for (ssize_t off = 0; n > 0 && off < n;) {
      const ssize_t w = ::write(to, b + off, static_cast<std::size_t>(n - off));
      if (w <= 0) return false;
      off += w;
    }
    return n > 0;
  }

  int master_;
  int sock_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(TcpUri, ReachesPalpSimAndRunsTheHandshakeAndDeviceInfo) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok()) << sim.banner();
  const std::string uri = "tcp://127.0.0.1:" + std::to_string(sim.device_port());
  palp::Probe probe(uri);
  EXPECT_EQ(probe.uri(), uri);
  EXPECT_EQ(probe.info().serial, "SIM-0001");
  EXPECT_EQ(probe.info().board, "palp-sim");
  EXPECT_EQ(probe.info().control_rate_Hz, 20000);
  EXPECT_FALSE(probe.handshake().missing_features);
  EXPECT_EQ(probe.status().state, palp::proto::DeviceState::idle);
}

TEST(TcpUri, NothingListeningIsAConnectionErrorNamingTheUriAsGiven) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok());
  const std::string uri = "tcp://127.0.0.1:" + std::to_string(sim.device_port());
  sim.stop();
  try {
    palp::open_transport(uri, 500ms);
    FAIL() << "connected to a stopped simulator";
  } catch (const palp::ConnectionError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot reach " + uri +
                                         ": Connection refused (is palp-sim, or QEMU with "
                                         "-serial tcp:HOST:PORT,server=on, listening there?)");
  }
}

/// palp-sim at real time behind a pty: serial:// + slave is the board's tty.
struct SerialSim {
  SimProcess sim{{}, false};
  PtyPair pty;
  PtyRelay relay{pty.master(), sim.device_port()};
  bool ok() { return sim.ok() && pty.ok() && relay.ok() && sim.control("pace 1") == "ok"; }
};

TEST(SerialUri, ASessionThroughAPtyHoldsACurrentAndStreamsEverySample) {
  SerialSim s;
  ASSERT_TRUE(s.ok()) << s.sim.banner();
  palp::Probe probe(s.pty.uri());
  EXPECT_EQ(probe.uri(), s.pty.uri());
  EXPECT_EQ(probe.info().serial, "SIM-0001");
  EXPECT_EQ(probe.info().board, "palp-sim");
  const palp::StreamInfo info = probe.configure_stream({.rate_Hz = 200.0});
  EXPECT_LE(info.wire_bytes_per_s, 11520u);
  probe.start_stream();
  palp::HoldProgram hold;
  hold.current_A = 0.3f;
  hold.duration_s = 0.3f;
  const palp::ProgramResult r = probe.run(hold, 10s);
  EXPECT_EQ(r.end, palp::proto::ProgramEnd::completed);
  probe.stop_stream();
  std::uint64_t samples = 0, next = 0, held = 0;
  bool in_order = true;
  while (auto item = probe.next(500ms)) {
    const auto* smp = std::get_if<palp::Sample>(&*item);
    ASSERT_NE(smp, nullptr) << "a gap in a stream over the pty";
    in_order = in_order && smp->index == next;
    next = smp->index + 1;
    ++samples;
    if (std::abs(smp->i_cmd_A - 0.3) < 1e-6) ++held;
  }
  EXPECT_TRUE(in_order);
  // 0.3 s of hold at 200 Hz is 60 samples, and the stream ran before and after it
  EXPECT_GE(held, 55u);
  EXPECT_GT(samples, held);
  EXPECT_EQ(probe.health().host_samples_missing, 0u);
}

TEST(SerialUri, AStreamBeyondWhatTheBaudCarriesIsRefusedNamingTheUri) {
  SerialSim s;
  ASSERT_TRUE(s.ok()) << s.sim.banner();
  palp::Probe probe(s.pty.uri());
  try {
    probe.configure_stream({.rate_Hz = 2000.0});
    FAIL() << "a 2 kHz stream of every channel was accepted at 115200 baud";
  } catch (const palp::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("but " + s.pty.uri() + " carries at most 11520 bytes/s"));
  }
  probe.close();  // the tty's lock goes with it
  palp::Probe faster(s.pty.uri() + "?baud=4000000");
  EXPECT_NO_THROW(faster.configure_stream({.rate_Hz = 2000.0})) << "4000000 baud carries it";
}

TEST(SerialUri, TheFarEndGoneMidSessionFailsTheNextRequestWithAConnectionError) {
  SerialSim s;
  ASSERT_TRUE(s.ok()) << s.sim.banner();
  palp::ConnectOptions o;
  o.reconnect = false;
  palp::Probe probe(s.pty.uri(), o);
  ASSERT_EQ(probe.status().state, palp::proto::DeviceState::idle);
  s.relay.stop();
  s.pty.close_master();
  const auto t0 = Clock::now();
  EXPECT_THROW(probe.status(), palp::ConnectionError);
  EXPECT_LT(Clock::now() - t0, o.timeout) << "it waited out the request's timeout";
}

TEST(SerialUri, ATtyThatComesBackUnderItsNameAfterAHangUpRestoresTheSession) {
  // A USB-serial adapter unplugged and plugged back gets its old name only once every file
  // open on the old one is closed: the SDK must let go of the hung-up tty before it reopens the
  // path. A pty behaves alike: its number is free again once the last fd on it is closed.
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_EQ(sim.control("pace 1"), "ok");
  auto pty = std::make_unique<PtyPair>();
  auto relay = std::make_unique<PtyRelay>(pty->master(), sim.device_port());
  ASSERT_TRUE(pty->ok() && relay->ok());
  const std::string name = pty->slave_name();
  palp::Probe probe(pty->uri());
  ASSERT_EQ(probe.status().state, palp::proto::DeviceState::idle);
  relay.reset();  // the board's side goes: the relay's connection to palp-sim, the pty
  pty.reset();
  // the board comes back: a pty is given the lowest free number, the old one once it is free
  const auto t0 = Clock::now();
  while (Clock::now() - t0 < 3s) {
    pty = std::make_unique<PtyPair>();
    if (pty->ok() && pty->slave_name() == name) break;
    pty.reset();
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_TRUE(pty) << name << " stayed taken: the SDK kept the hung-up tty open";
  relay = std::make_unique<PtyRelay>(pty->master(), sim.device_port());
  ASSERT_TRUE(relay->ok());
  EXPECT_EQ(probe.status().state, palp::proto::DeviceState::idle);
  EXPECT_EQ(probe.health().reconnects, 1u);
}

}  // namespace
