// SPDX-License-Identifier: Apache-2.0
// The simulation's rules (hil/README.md) with the real firmware core and the real plant:
// results independent of how the run is chunked, a contact event holding virtual time until the
// host reacts, the reaction latency in virtual time, the wall-clock hold timeout, and frame loss
// injected after the firmware (seen by the host as index gaps, never hidden).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "palp/sim/plant_link.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim {
namespace {

using namespace palp::proto;

template <class M>
void send(Simulation& s, const M& m, u16 seq, std::uint64_t wall_us) {
  std::vector<u8> w(kMaxWireFrame);
  w.resize(encode_message(m, seq, 0, w.data(), w.size()));
  s.host_bytes(w.data(), w.size(), wall_us);
}

/// A simulation with a host session open (Hello sent at wall time 0, its DeviceInfo dropped).
std::unique_ptr<Simulation> make(std::uint64_t seed = 1) {
  fw::DeviceIdentity id;
  id.board = "palp-sim";
  auto s = std::make_unique<Simulation>(id, std::make_unique<ModelPlant>("none", seed));
  send(*s, Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "test"}, 0, 0);
  s->take_device_bytes();
  return s;
}

struct HostView {
  FrameReader reader;
  std::vector<SampleBatch> batches;
  std::vector<EventContact> contacts;
  std::vector<EventStreamGap> gaps;
  std::uint32_t rejected = 0;
  void take(Simulation& s) {
    const std::vector<u8> bytes = s.take_device_bytes();
    reader.feed_messages(
        bytes.data(), bytes.size(),
        [&](const FrameHeader&, const auto& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, SampleBatch>) batches.push_back(m);
          if constexpr (std::is_same_v<M, EventContact>) contacts.push_back(m);
          if constexpr (std::is_same_v<M, EventStreamGap>) gaps.push_back(m);
        },
        [&](Reject) { ++rejected; });
  }
};

// Runs n ticks in chunks of `chunk`, feeding the watchdog with wall time that moves with it.
void run(Simulation& s, HostView& host, std::uint64_t n, std::uint32_t chunk, std::uint64_t& wall) {
  std::uint64_t done = 0;
  while (done < n) {
    const std::uint32_t want = static_cast<std::uint32_t>(std::min<std::uint64_t>(chunk, n - done));
    const std::uint32_t ran = s.run(want, wall);
    done += ran;
    wall += 1000;
    host.take(s);
    if (s.holding()) break;  // a held event waits for the host's reaction: the test decides it
    send(s, Heartbeat{}, 99, wall);
    if (ran == 0) break;
  }
}

TEST(Simulation, TheSameSeedGivesTheSameSamplesHoweverTheRunIsChunked) {
  std::vector<std::vector<SampleBatch>> results;
  for (std::uint32_t chunk : {7u, 20u, 333u}) {
    auto s = make(42);
    HostView host;
    std::uint64_t wall = 0;
    send(*s, LoadHold{0.7f, 0.0f}, 1, wall);
    send(*s, ProgramStart{}, 2, wall);
    send(*s, StreamConfigure{kAllChannels, 2, 40}, 3, wall);
    send(*s, StreamStart{}, 4, wall);
    run(*s, host, 4000, chunk, wall);
    results.push_back(host.batches);
  }
  ASSERT_FALSE(results[0].empty());
  ASSERT_EQ(results[0].size(), results[1].size());
  ASSERT_EQ(results[0].size(), results[2].size());
  for (std::size_t k = 0; k < results[0].size(); ++k) {
    EXPECT_EQ(results[0][k], results[1][k]) << "batch " << k;
    EXPECT_EQ(results[0][k], results[2][k]) << "batch " << k;
  }
}

TEST(Simulation, AContactEventHoldsVirtualTimeUntilTheHostReactsThenAppliesTheLatency) {
  auto s = make();
  HostView host;
  std::uint64_t wall = 0;
  s->options().reaction_latency_ms = 5.0;
  s->options().hold_timeout_ms = 60'000.0;
  // free air: 0.7 A pushes the coil forward from its float position; 200 um fire the watch
  send(*s, LoadContactWatch{0.7f, 200, 0.0f}, 1, wall);
  send(*s, ProgramStart{}, 2, wall);
  for (int k = 0; k < 400 && host.contacts.empty(); ++k) run(*s, host, 20, 20, wall);
  ASSERT_EQ(host.contacts.size(), 1u);
  ASSERT_TRUE(s->holding());
  const std::uint64_t held_at = s->ticks();
  EXPECT_EQ(s->run(1000, wall + 10'000), 0u);  // wall time passes, virtual time does not
  EXPECT_EQ(s->ticks(), held_at);
  // the host reacts (after a long wall-clock pause): its frame lands 5 ms of virtual time later
  send(*s, ProgramStop{}, 3, wall + 50'000);
  EXPECT_FALSE(s->holding());
  s->run(200, wall + 50'000);
  EXPECT_EQ(s->ticks(), held_at + 200);
  EXPECT_EQ(s->counters().holds, 1u);
  EXPECT_EQ(s->counters().hold_timeouts, 0u);
  // the stop took effect at held_at + 100 ticks (5 ms at 20 kHz): the controller reports the
  // finished program with that device time
  host.take(*s);
}

TEST(Simulation, ARobotWriteIsAReactionThatLandsTheLatencyAfterTheHold) {
  auto s = make();
  HostView host;
  std::uint64_t wall = 0;
  s->options().reaction_latency_ms = 5.0;
  s->options().hold_timeout_ms = 60'000.0;
  EXPECT_EQ(s->host_reaction(wall), s->ticks());  // nothing held: at once
  send(*s, LoadContactWatch{0.7f, 200, 0.0f}, 1, wall);
  send(*s, ProgramStart{}, 2, wall);
  for (int k = 0; k < 400 && host.contacts.empty(); ++k) run(*s, host, 20, 20, wall);
  ASSERT_TRUE(s->holding());
  const std::uint64_t held_at = s->ticks();
  EXPECT_TRUE(s->contact_line() == false);  // contact output disabled by default
  // the robot client's stop write, long after in wall time: 5 ms = 100 ticks after the hold
  EXPECT_EQ(s->host_reaction(wall + 50'000), held_at + 100);
  EXPECT_FALSE(s->holding());
  EXPECT_EQ(s->host_reaction(wall + 50'001), held_at + 100);  // a second one lands with it
  EXPECT_EQ(s->run(200, wall + 50'000), 200u);
  EXPECT_EQ(s->counters().hold_timeouts, 0u);
}

TEST(Simulation, AHostThatNeverReactsReleasesTheHoldAfterTheWallTimeout) {
  auto s = make();
  HostView host;
  std::uint64_t wall = 0;
  s->options().hold_timeout_ms = 100.0;
  send(*s, LoadContactWatch{0.7f, 200, 0.0f}, 1, wall);
  send(*s, ProgramStart{}, 2, wall);
  for (int k = 0; k < 400 && host.contacts.empty(); ++k) run(*s, host, 20, 20, wall);
  ASSERT_TRUE(s->holding());
  const std::uint64_t held_at = s->ticks();
  EXPECT_EQ(s->run(20, wall + 98'000), 0u);  // the event came 1 ms of wall time before `wall`
  EXPECT_EQ(s->run(20, wall + 101'000), 20u);
  EXPECT_EQ(s->ticks(), held_at + 20);
  EXPECT_EQ(s->counters().hold_timeouts, 1u);
}

TEST(Simulation, DroppedFramesReachTheHostAsIndexGapsNeverAsHiddenLoss) {
  auto s = make();
  HostView host;
  std::uint64_t wall = 0;
  send(*s, StreamConfigure{kAllChannels, 2, 40}, 1, wall);
  send(*s, StreamStart{}, 2, wall);
  s->options().drop_every = 10;
  run(*s, host, 20000, 100, wall);  // 1 s: 10000 samples, 250 batches
  std::uint32_t expected = 0, seen = 0, holes = 0;
  for (const SampleBatch& b : host.batches) {
    if (b.first_index != expected) holes += b.first_index - expected;
    expected = b.first_index + b.sample_count;
    seen += b.sample_count;
  }
  EXPECT_GT(s->counters().frames_dropped, 0u);
  EXPECT_GT(holes, 0u);
  EXPECT_EQ(seen + holes, expected);  // every index accounted for: received or a visible hole
}

}  // namespace
}  // namespace palp::sim
