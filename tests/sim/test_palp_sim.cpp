// SPDX-License-Identifier: Apache-2.0
// palp-sim as a process, over real loopback sockets: the device protocol, malformed input, the
// control channel, announced versions and the firmware core driving the physical model.
#include <gtest/gtest.h>

#include <random>

#include "sim_process.hpp"

namespace palp::sim::test {
namespace {

using namespace palp::proto;

TEST(PalpSim, AnswersTheHandshakeOverTcpAsAPalpSimDevice) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  sim.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "test"}, 1);
  DeviceInfo d;
  ASSERT_TRUE(sim.await(1, d));
  EXPECT_EQ(std::string(d.board.bytes.data()), "palp-sim");
  EXPECT_EQ(d.schema_hash, kSchemaHash);
  EXPECT_EQ(d.state, DeviceState::idle);
  EXPECT_NE(d.capabilities & (1u << static_cast<unsigned>(Capability::simulated)), 0u);
}

// SPEC.md §6.2: every connection is a new session; before its Hello only identify is served.
TEST(PalpSim, ANewClientIsRefusedHelloRequiredUntilItsOwnHello) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  sim.send(GetStatus{}, 1);
  Status st;
  ASSERT_TRUE(sim.await(1, st));  // the first client said Hello (SimProcess does)
  ASSERT_TRUE(sim.reconnect_without_hello());
  sim.send(LoadHold{0.3f, 0.0f}, 2);
  Nak n;
  ASSERT_TRUE(sim.await(2, n));
  EXPECT_EQ(n.error, ErrorCode::hello_required);
  EXPECT_EQ(n.request_id, static_cast<u8>(MessageId::LoadHold));
  sim.send(GetDeviceInfo{}, 3);
  DeviceInfo d;
  ASSERT_TRUE(sim.await(3, d));
  sim.hello();
  sim.send(GetStatus{}, 4);
  ASSERT_TRUE(sim.await(4, st));
  EXPECT_EQ(st.state, DeviceState::idle);  // nothing was loaded or started
}

TEST(PalpSim, MalformedBytesNeitherCrashNorWedgeIt) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  std::mt19937 rng(99);
  std::vector<u8> junk(256 * 1024);
  for (auto& b : junk) b = static_cast<u8>(rng() % 7 == 0 ? 0 : rng());
  sim.send_bytes(junk);
  sim.send_bytes({0x00});
  sim.send(Ping{7, 8}, 42);
  Pong p;
  ASSERT_TRUE(sim.await(42, p)) << "no Pong after 256 KiB of garbage";
  EXPECT_EQ(p.nonce, 7u);
  EXPECT_TRUE(sim.alive());
  sim.send(GetHealth{}, 43);
  Health h;
  ASSERT_TRUE(sim.await(43, h));
  EXPECT_GT(h.rx_bad_cobs + h.rx_bad_crc + h.rx_truncated + h.rx_oversize, 0u);
}

TEST(PalpSim, AHoldProgramDrivesTheSimulatedCoil) {
  SimProcess sim({"--phantom", "none"});
  ASSERT_TRUE(sim.ok()) << sim.banner();
  sim.send(LoadHold{0.6f, 0.0f}, 1);
  Ack a;
  ASSERT_TRUE(sim.await(1, a));
  sim.send(ProgramStart{}, 2);
  ASSERT_TRUE(sim.await(2, a));
  Status s;
  sim.send(GetStatus{}, 3);
  ASSERT_TRUE(sim.await(3, s));
  // 1.5 s of virtual time after the start (the ring-down is over); the start itself comes a
  // wall-time-dependent while after boot (a few ms of setup at over 200x: up to ~1.5 s)
  const std::uint64_t started_us = s.device_time_us;
  for (u16 seq = 4; seq < 4000; ++seq) {
    sim.send(GetStatus{}, seq);
    ASSERT_TRUE(sim.await(seq, s));
    if (s.device_time_us > started_us + 1'500'000) break;
  }
  EXPECT_EQ(s.state, DeviceState::running);
  EXPECT_NEAR(s.i_A, 0.6f, 0.02f);
  // free air: 0.1 A above the float current moves the coil forward by 0.1 A x 2.918 N/A /
  // 43.9 N/m = 6.6 mm from its float position at 25 mm (hil/plant/README.md)
  EXPECT_NEAR(s.encoder_count, 25000 + 6647, 300);
  EXPECT_EQ(s.fault, FaultReason::none);
}

TEST(PalpSim, AHostThatDoesNotReadStallsVirtualTimeAndLosesNoSample) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  sim.send(StreamConfigure{kAllChannels, 2, 40}, 1);
  sim.send(StreamStart{}, 2);
  // the host reads nothing for 0.7 s of wall time, but is alive: a heartbeat every 0.1 s (a
  // host silent for the heartbeat timeout is lost, and its frames are dropped: hil/README.md)
  for (u16 k = 0; k < 7; ++k) {
    sim.send(Heartbeat{}, static_cast<u16>(100 + k));
    ::usleep(100'000);
  }
  // now drain until the device time of a Status shows the stream kept going; count the samples
  std::uint32_t expected = 0, samples = 0, gaps = 0;
  Status st;
  u16 seq = 10;
  for (int round = 0; round < 50; ++round) {
    sim.send(GetStatus{}, ++seq);
    ASSERT_TRUE(sim.await_collecting(seq, st, [&](const auto& m) {
      using M = std::decay_t<decltype(m)>;
      if constexpr (std::is_same_v<M, SampleBatch>) {
        if (m.first_index != expected) ++gaps;
        expected = m.first_index + m.sample_count;
        samples += m.sample_count;
      }
      if constexpr (std::is_same_v<M, EventStreamGap>) ++gaps;
    }));
  }
  EXPECT_EQ(gaps, 0u);
  EXPECT_GT(samples, 10000u);  // more than a second of stream went through the stalled link
  sim.send(GetHealth{}, ++seq);
  Health h;
  ASSERT_TRUE(sim.await(seq, h));
  EXPECT_EQ(h.stream_samples_lost, 0u);
  EXPECT_EQ(h.isr_queue_overflows, 0u);
}

TEST(PalpSim, TheControlChannelAnswersEveryLine) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  EXPECT_EQ(sim.control("status").rfind("ok virtual_s=", 0), 0u);
  EXPECT_EQ(sim.control("mount 1 2 3"), "ok");
  EXPECT_EQ(sim.control("fly"), "error: unknown command 'fly'; try 'help'");
  EXPECT_EQ(sim.control("phantom no_such_phantom").rfind("error: ", 0), 0u);
}

TEST(PalpSim, AnnouncesAnotherProtocolWhenToldSoTheHostSeesIt) {
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_EQ(sim.control("announce 3.7 0x12345678"), "ok");
  sim.send(GetDeviceInfo{}, 5);
  DeviceInfo d;
  ASSERT_TRUE(sim.await(5, d));
  EXPECT_EQ(d.protocol_major, 3);
  EXPECT_EQ(d.protocol_minor, 7);
  EXPECT_EQ(d.schema_hash, 0x12345678u);
}

}  // namespace
}  // namespace palp::sim::test
