// SPDX-License-Identifier: Apache-2.0
// sim::Server, palp-sim's loop, driven step by step in the test's thread with real loopback
// sockets: pacing at a factor, the stall while the host has not drained, a held contact event,
// and a control-channel command.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "palp/protocol/frame.hpp"
#include "palp/protocol/stream.hpp"
#include "palp/sim/server.hpp"
#include "server_client.hpp"

namespace palp::sim {
namespace {

using namespace std::chrono_literals;
using test::Client;
using test::make_server;
using test::control_port;
using test::step_until;
using Clock = std::chrono::steady_clock;

TEST(SimServer, AtHalfRealTimeVirtualTimeNeverRunsAheadOfHalfTheWallTime) {
  auto s = make_server(0.5);
  Client host(s->device().port());
  ASSERT_GE(host.fd, 0);
  // the wall clock starts before the step that accepts, where the pace's anchor is taken: a
  // slow step (ASan) must not count against the pace (it did: 1.5 ms "ahead" under load)
  const auto t0 = Clock::now();
  s->step();  // accepts: the pace counts from here
  double worst_lead_s = -1;
  while (Clock::now() - t0 < 300ms) {
    s->step();
    const double wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
    worst_lead_s = std::max(worst_lead_s, s->instrument().simulation().virtual_s() - 0.5 * wall_s);
  }
  EXPECT_LE(worst_lead_s, 1e-3);  // at most the step's own chunk ahead
  EXPECT_GT(s->instrument().simulation().virtual_s(), 0.0);  // and it did run
}

TEST(SimServer, AHostThatDoesNotDrainStopsVirtualTimeAndNothingIsDropped) {
  auto s = make_server(0);
  Client host(s->device().port(), 4096);
  ASSERT_GE(host.fd, 0);
  host.hello();
  // a heartbeat timeout beyond the test: a host silent for it is lost, and no longer stalls
  // (test_server_host_loss.cpp)
  proto::SetParams p;
  p.heartbeat_timeout_ms = 10000;
  host.send(p, 5);
  host.send(proto::StreamConfigure{proto::kAllChannels, 1, 40}, 1);
  host.send(proto::StreamStart{}, 2);
  // the host reads nothing: the socket buffers and the server's queue fill, then time stops
  const Simulation& sim = s->instrument().simulation();
  std::uint64_t last = 0;
  int still = 0;
  ASSERT_TRUE(step_until(*s, [&] {
    still = sim.ticks() == last ? still + 1 : 0;
    last = sim.ticks();
    return still >= 200;
  }, 60s));
  EXPECT_EQ(sim.counters().frames_dropped, 0u);
  // reading lets it go on
  host.take();
  const std::uint64_t stalled = sim.ticks();
  EXPECT_TRUE(step_until(*s, [&] {
    host.take();
    return sim.ticks() > stalled + 2000;
  }, 60s));
}

TEST(SimServer, AContactEventHoldsVirtualTimeUntilTheHostsNextFrame) {
  // the coil floating at 0.5 A reaches the solid's top 25 mm below the mount; a hold timeout
  // far beyond the test's steps, however slow the machine
  auto s = make_server(0, {.phantom = "solid_1d", .mount_mm = {27, 0, -25}, .hold_timeout_ms = 60e3});
  Client host(s->device().port());
  ASSERT_GE(host.fd, 0);
  proto::SetParams p;  // a host silent for the heartbeat timeout ends a hold: beyond the test
  p.heartbeat_timeout_ms = 10000;
  host.hello();
  host.send(p, 5);
  proto::LoadContactWatch w;
  w.hold_current_A = 0.5f;
  w.threshold_counts = 500;
  host.send(w, 1);
  host.send(proto::ProgramStart{}, 2);
  Simulation& sim = s->instrument().simulation();
  ASSERT_TRUE(step_until(*s, [&] {
    host.take();
    return sim.holding();
  }));
  const std::uint64_t held = sim.ticks();
  for (int k = 0; k < 100; ++k) s->step();  // well within the 1 s hold timeout
  EXPECT_EQ(sim.ticks(), held);
  host.send(proto::Heartbeat{}, 3);
  ASSERT_TRUE(step_until(*s, [&] { return sim.ticks() > held; }));
  EXPECT_FALSE(sim.holding());
  EXPECT_EQ(sim.counters().holds, 1u);
  EXPECT_EQ(sim.counters().hold_timeouts, 0u);
}

TEST(SimServer, AControlLineIsAnsweredAndChangesThePace) {
  auto s = make_server(1);
  Client control(control_port(*s));
  ASSERT_GE(control.fd, 0);
  control.send_text("pace 4\nstatus\nmount 1 2\n");
  std::string answers;
  ASSERT_TRUE(step_until(*s, [&] {
    answers += control.take();
    return std::count(answers.begin(), answers.end(), '\n') >= 3;
  }));
  EXPECT_EQ(s->pace(), 4.0);
  EXPECT_EQ(answers.substr(0, 3), "ok\n");
  EXPECT_NE(answers.find("ok virtual_s="), std::string::npos);
  EXPECT_NE(answers.find(" pace=4 client=0 "), std::string::npos);
  EXPECT_NE(answers.find("\nerror: mount"), std::string::npos) << answers;
}

TEST(SimServer, AModbusServerWithoutTheRobotOnIsRefused) {
  EXPECT_THROW(Server(std::make_unique<Instrument>(InstrumentOptions{}),
                      ByteServer::tcp("127.0.0.1", 0), ByteServer::tcp("127.0.0.1", 0),
                      std::make_unique<ModbusServer>("127.0.0.1", 0), 1.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace palp::sim
