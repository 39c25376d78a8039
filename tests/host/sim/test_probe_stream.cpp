// SPDX-License-Identifier: Apache-2.0
// Streaming from palp-sim through the SDK: order, no loss at 10 kHz, every loss reported as a
// gap record with its source, back-pressure, the device-to-host clock mapping and reconnect.
// Reconnect and the clock mapping's pace run palp-sim as a process over a socket (restarting
// and killing it, pacing in real time); the rest palp-sim linked in (palp/sim_inproc.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <thread>

#include "palp/log.hpp"
#include "palp/probe.hpp"
#include "palp/sim_inproc.hpp"
#include "sim_process.hpp"

namespace {

using namespace std::chrono_literals;
using palp::Gap;
using palp::Sample;
using palp::StreamItem;
using palp::sim::InprocSimulator;
using palp::sim::test::SimProcess;
using testing::HasSubstr;

/// Walks items and checks the stream's bookkeeping: every index from the first on is either a
/// sample or inside exactly one gap, in order. Returns samples and missing counts.
struct Tally {
  std::uint64_t samples = 0, missing = 0, gaps = 0, next = 0;
  bool in_order = true;
  std::vector<Gap> gap_list;
  void add(const StreamItem& item) {
    if (const Sample* s = std::get_if<Sample>(&item)) {
      in_order = in_order && s->index == next;
      next = s->index + 1;
      ++samples;
    } else {
      const Gap& g = std::get<Gap>(item);
      in_order = in_order && g.first_index == next;
      next = g.first_index + g.count;
      missing += g.count;
      ++gaps;
      gap_list.push_back(g);
    }
  }
};

TEST(ProbeStream, AMillionSamplesAt10kHzArriveInOrderWithNoneLost) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  const palp::StreamInfo info = probe.configure_stream({.rate_Hz = 10000.0});
  EXPECT_DOUBLE_EQ(info.period_s, 1e-4);
  EXPECT_EQ(info.batch_samples, 40);  // all 11 channels: 24-byte samples, 960 data bytes
  probe.start_stream();
  Tally t;
  std::vector<StreamItem> items;
  double last_t = -1;
  bool times_exact = true;
  while (t.samples + t.missing < 1'000'000) {
    items.clear();
    if (probe.drain(items) == 0) {
      if (auto one = probe.next(5s)) items.push_back(*one);
      else break;
    }
    for (const StreamItem& item : items) {
      t.add(item);
      if (const Sample* s = std::get_if<Sample>(&item)) {
        times_exact = times_exact && (last_t < 0 || std::abs(s->t_device_s - last_t - 1e-4) < 1e-9);
        last_t = s->t_device_s;
      }
    }
  }
  probe.stop_stream();
  EXPECT_TRUE(t.in_order);
  EXPECT_GE(t.samples, 1'000'000u);
  EXPECT_EQ(t.missing, 0u);
  EXPECT_EQ(t.gaps, 0u);
  EXPECT_TRUE(times_exact) << "sample times are not exactly 100 us apart";
  const palp::HealthCounters h = probe.health();
  EXPECT_EQ(h.host_samples_missing, 0u);
  EXPECT_EQ(h.stream_samples_lost, 0u);
  EXPECT_EQ(h.host_rx_rejected, 0u);
}

TEST(ProbeStream, FramesTheSimulatorDropsBecomeTransportGapsThatAccountForEveryIndex) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  probe.configure_stream({.rate_Hz = 10000.0});
  probe.start_stream();
  ASSERT_EQ(sim.control("drop-frames 5"), "ok");
  Tally t;
  while (t.samples + t.missing < 50'000) {
    auto item = probe.next(5s);
    ASSERT_TRUE(item.has_value()) << "the stream stopped";
    t.add(*item);
  }
  ASSERT_EQ(sim.control("drop-frames 0"), "ok");
  EXPECT_TRUE(t.in_order);
  EXPECT_GT(t.gaps, 0u);
  for (const Gap& g : t.gap_list) {
    EXPECT_EQ(g.source, palp::GapSource::transport);
    EXPECT_EQ(g.count % 40, 0u) << "a dropped frame is a whole batch of 40 samples";
    EXPECT_TRUE(g.count_known);
  }
  // the queue's own counters agree with the records
  const palp::HealthCounters h = probe.health();
  EXPECT_GE(h.host_samples_missing, t.missing);
  EXPECT_EQ(h.host_queue_dropped, 0u);
}

TEST(ProbeStream, AFullHostQueueDropsTheNewestSamplesAsOneHostQueueGap) {
  InprocSimulator sim;
  palp::ConnectOptions o;
  o.queue_items = 1000;
  palp::Probe probe(sim.transport(), o);
  probe.configure_stream({.rate_Hz = 10000.0});
  probe.start_stream();
  std::this_thread::sleep_for(300ms);  // 300 ms at >= 1x: far more than 1000 samples
  probe.stop_stream();
  std::vector<StreamItem> items;
  probe.drain(items);
  Tally t;
  for (const StreamItem& item : items) t.add(item);
  EXPECT_TRUE(t.in_order);
  EXPECT_EQ(t.samples, 1000u);
  ASSERT_EQ(t.gap_list.size(), 1u);
  EXPECT_EQ(t.gap_list[0].source, palp::GapSource::host_queue);
  EXPECT_EQ(t.gap_list[0].first_index, 1000u);
  const palp::HealthCounters h = probe.health();
  EXPECT_EQ(h.host_queue_dropped, t.gap_list[0].count);
  EXPECT_EQ(h.host_queue_max, 1000u);
}

TEST(ProbeStream, TheClockMappingFollowsTheSimulatorsPaceAndItsChange) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok());
  ASSERT_EQ(sim.control("pace 1"), "ok");
  palp::Probe probe(sim.uri());
  std::this_thread::sleep_for(1500ms);
  EXPECT_NEAR(probe.clock().drift, 0.0, 0.02) << "real time: one host second per device second";
  ASSERT_EQ(sim.control("pace 2"), "ok");
  std::this_thread::sleep_for(3000ms);
  const palp::ClockMapping c = probe.clock();
  EXPECT_NEAR(c.drift, -0.5, 0.03) << "twice real time: half a host second per device second";
  EXPECT_GE(c.points, 3u);
  // a sample's host time is close to when it was taken
  probe.configure_stream({.rate_Hz = 1000.0});
  probe.start_stream();
  auto item = probe.next(2s);
  ASSERT_TRUE(item.has_value());
  const double now = std::chrono::duration<double>(
                         std::chrono::steady_clock::now().time_since_epoch()).count();
  const Sample& s = std::get<Sample>(*item);
  EXPECT_NEAR(s.t_host_s, now, 0.2);
}

TEST(ProbeStream, ARestartedSimulatorRestoresTheSessionAndTheStreamAfterAReconnectGap) {
  auto sim = std::make_unique<SimProcess>(std::vector<std::string>{}, false);
  ASSERT_TRUE(sim->ok());
  const std::uint16_t port = sim->device_port();
  // the recovery is reported through the log handler (palp/log.hpp), not kept silent
  std::mutex log_mu;
  std::string log;
  palp::set_log_handler([&](palp::LogLevel level, const std::string& message) {
    std::lock_guard lock(log_mu);
    log += std::string(palp::log_level_name(level)) + ": " + message + "\n";
  });
  struct Unset {
    ~Unset() { palp::set_log_handler(nullptr); }
  } unset;
  palp::Probe probe(sim->uri());
  probe.configure_stream({.rate_Hz = 1000.0});
  probe.start_stream();
  Tally t;
  // 3 s of device time before the restart: the new simulator's clock, which runs from 0 at
  // its fast pace while the SDK reconnects, stays well behind it (the SDK tells a restarted
  // clock from one that ran on by the first batch's time; 200 samples left that a race)
  while (t.samples < 3000) t.add(*probe.next(5s));
  sim->stop();
  sim = std::make_unique<SimProcess>(std::vector<std::string>{}, false, port);
  ASSERT_TRUE(sim->ok()) << sim->banner();
  // the queue may still hold samples the old simulator sent after the 3000th: the new ones are
  // those after the reconnect gap
  const auto end = std::chrono::steady_clock::now() + 10s;
  bool reconnected = false;
  std::uint64_t new_samples = 0;
  while ((!reconnected || new_samples < 200) && std::chrono::steady_clock::now() < end) {
    auto item = probe.next(1s);
    if (!item) continue;
    t.add(*item);
    if (const Gap* g = std::get_if<Gap>(&*item); g && g->source == palp::GapSource::reconnect)
      reconnected = true;
    else if (reconnected && std::holds_alternative<Sample>(*item))
      ++new_samples;
  }
  EXPECT_TRUE(t.in_order);
  ASSERT_FALSE(t.gap_list.empty());
  const Gap& g = t.gap_list.back();
  EXPECT_EQ(g.source, palp::GapSource::reconnect);
  EXPECT_FALSE(g.count_known) << "a restarted simulator's clock starts again at 0";
  EXPECT_GE(new_samples, 200u);
  EXPECT_EQ(probe.health().reconnects, 1u);
  EXPECT_EQ(probe.status().state, palp::proto::DeviceState::idle);
  std::lock_guard lock(log_mu);
  EXPECT_THAT(log, HasSubstr("info: connected to "));
  EXPECT_THAT(log, testing::ContainsRegex("warning: the link to [^ ]+ was lost \\(.*\\): reconnecting\n"));
  EXPECT_THAT(log, testing::ContainsRegex("info: the link to [^ ]+ was restored and the stream restarted\n"));
  EXPECT_THAT(log, testing::ContainsRegex(
                       "warning: stream gap: an unknown number of samples missing from index [0-9]+ \\(reconnect\\)\n"));
}

TEST(ProbeStream, ALinkThatStaysDownFailsEveryCallWithWhyAndForHowLong) {
  auto sim = std::make_unique<SimProcess>(std::vector<std::string>{}, false);
  ASSERT_TRUE(sim->ok());
  palp::ConnectOptions o;
  o.reconnect_for = 300ms;
  palp::Probe probe(sim->uri(), o);
  sim->stop();
  std::this_thread::sleep_for(800ms);
  try {
    probe.status();
    FAIL() << "status() answered without a device";
  } catch (const palp::ConnectionError& e) {
    EXPECT_THAT(e.what(), HasSubstr("could not be restored within 300 ms"));
    EXPECT_THAT(e.what(), HasSubstr("palp-sim"));
  }
}

TEST(ProbeStream, ACallbackReceivesTheItemsInOrderInsteadOfTheQueue) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  std::mutex mu;
  Tally t;
  probe.on_stream([&](const StreamItem& item) {
    std::lock_guard lock(mu);
    t.add(item);
  });
  probe.configure_stream({.rate_Hz = 5000.0});
  probe.start_stream();
  for (int k = 0; k < 500; ++k) {
    {
      std::lock_guard lock(mu);
      if (t.samples >= 20000) break;
    }
    std::this_thread::sleep_for(10ms);
  }
  probe.stop_stream();
  EXPECT_FALSE(probe.next(10ms).has_value()) << "with a callback nothing goes to the queue";
  std::lock_guard lock(mu);
  EXPECT_GE(t.samples, 20000u);
  EXPECT_TRUE(t.in_order);
  EXPECT_EQ(t.missing, 0u);
}

TEST(ProbeShutdown, ClosingDuringAProgramLeavesTheDeviceWithZeroCurrent) {
  InprocSimulator sim;
  {
    palp::Probe probe(sim.transport());
    palp::HoldProgram h;
    h.current_A = 0.4f;
    h.duration_s = 0.0f;  // until stopped
    probe.load(h);
    probe.start();
    EXPECT_EQ(probe.status().program_state, palp::proto::ProgramState::running);
  }  // the destructor closes
  palp::Probe again(sim.transport());
  const palp::Status st = again.status();
  EXPECT_NE(st.program_state, palp::proto::ProgramState::running);
  EXPECT_EQ(st.i_cmd_A, 0.0);
  EXPECT_FALSE(st.streaming);
}

TEST(ProbeStream, WithReconnectOffALostLinkFailsEveryCallAtOnceSayingSo) {
  auto sim = std::make_unique<SimProcess>(std::vector<std::string>{}, false);
  ASSERT_TRUE(sim->ok());
  palp::ConnectOptions o;
  o.reconnect = false;
  palp::Probe probe(sim->uri(), o);
  sim->stop();
  std::this_thread::sleep_for(200ms);
  try {
    probe.status();
    FAIL() << "status() answered without a device";
  } catch (const palp::ConnectionError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ConnectOptions::reconnect is off: connect again"));
  }
}

}  // namespace
