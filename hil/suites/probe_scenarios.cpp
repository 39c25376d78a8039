// SPDX-License-Identifier: Apache-2.0
// Probe scenarios: known answers that hold on palp-sim and on a real probe controller alike.
// The public SDK only (bench.hpp); what each one proves is in README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <thread>

#include "bench.hpp"
#include "palp/protocol/schema.hpp"

namespace palp::hil {
namespace {

using namespace std::chrono_literals;

bool bit(std::uint16_t bits, proto::StatusBit b) {
  return (bits >> static_cast<unsigned>(b)) & 1u;
}

using Identify = Scenario;
TEST_F(Identify, TheDeviceNamesItselfAndSpeaksThisSdksProtocol) {
  const DeviceInfo& d = probe().info();
  EXPECT_FALSE(d.serial.empty());
  EXPECT_FALSE(d.firmware_version.empty());
  EXPECT_EQ(d.protocol_major, proto::kProtocolMajor);
  if (d.protocol_minor == proto::kProtocolMinor) {
    EXPECT_EQ(d.schema_hash, proto::kSchemaHash) << "same version, another catalogue";
  }
  EXPECT_TRUE(d.control_rate_Hz == 20000 || d.control_rate_Hz == 40000) << d.control_rate_Hz;
  const Status st = probe().status();
  EXPECT_EQ(st.state, proto::DeviceState::idle);
  EXPECT_EQ(st.fault, proto::FaultReason::none);
  EXPECT_EQ(st.i_cmd_A, 0.0);
}

using Heartbeat = Scenario;
TEST_F(Heartbeat, KeepsAThreeSecondHoldAliveUnderA200msWatchdog) {
  Params p = saved_params();
  p.heartbeat_timeout_ms = 200;
  probe().set_params(p);
  ASSERT_EQ(probe().params().heartbeat_timeout_ms, 200u);
  HoldProgram h;
  h.current_A = 0.3f;
  h.duration_s = 0.0f;  // until stopped: the hold lasts 3 s of wall time whatever the pace
  probe().load(h);
  probe().start();
  const Status armed = probe().status();
  EXPECT_TRUE(bit(armed.status_bits, proto::StatusBit::heartbeat_armed));
  std::this_thread::sleep_for(3s);  // no request of ours: only the SDK's heartbeat feeds it
  const Status st = probe().status();
  EXPECT_EQ(st.fault, proto::FaultReason::none) << probe().fault().text;
  EXPECT_EQ(st.state, proto::DeviceState::running);
  EXPECT_EQ(st.program, proto::ProgramKind::hold);
  probe().stop();
  EXPECT_EQ(probe().wait(2s).end, proto::ProgramEnd::stopped_by_host);
  EXPECT_EQ(probe().fault().reason, proto::FaultReason::none);
}

using Hold = Scenario;
TEST_F(Hold, MeasuredCurrentIsWithin2PercentOf0_3AOverTheLast0_3s) {
  const double rate_Hz = stream_rate_at_most(probe().info(), 1000.0);  // 1 kHz but on a slow link
  probe().configure_stream({.rate_Hz = rate_Hz, .channels = channel::i_cmd | channel::i_meas});
  probe().start_stream();
  HoldProgram h;
  h.current_A = 0.3f;
  h.duration_s = 0.5f;
  const ProgramResult r = probe().run(h, 30s);
  EXPECT_EQ(r.end, proto::ProgramEnd::completed);
  std::vector<Gap> gaps;
  const std::vector<Sample> s = samples_until(probe(), r.t_device_s + 0.01, gaps);
  probe().stop_stream();
  EXPECT_EQ(gaps_text(gaps), "");
  std::vector<double> held;  // measured current while 0.3 A was commanded
  for (const Sample& x : s)
    if (std::fabs(x.i_cmd_A - 0.3) < kLsb_A / 2) held.push_back(x.i_A);
  ASSERT_NEAR(static_cast<double>(held.size()), 0.5 * rate_Hz, 1.0) << "0.5 s of samples";
  const auto last = static_cast<std::size_t>(0.3 * rate_Hz);
  double sum = 0;
  for (std::size_t k = held.size() - last; k < held.size(); ++k) sum += held[k];
  EXPECT_NEAR(sum / static_cast<double>(last), 0.3, 0.02 * 0.3);
}

using Ramp = Scenario;
TEST_F(Ramp, TheCommandedStaircaseIsExactSampleBySampleAndTheProgramCompletes) {
  const double rate_Hz = stream_rate_at_most(probe().info(), 1000.0);
  const double period_s = 1.0 / rate_Hz;
  const auto per_stair = static_cast<std::size_t>(std::lround(0.05 * rate_Hz));
  probe().configure_stream({.rate_Hz = rate_Hz});
  probe().start_stream();
  RampProgram r;
  r.start_A = 0.5f;
  r.stop_A = 1.0f;
  r.step_A = 0.1f;
  r.dwell_s = 0.05f;
  r.repetitions = 1;
  r.unload = 1;
  r.displacement_limit_counts = 0;
  const ProgramResult res = probe().run(r, 30s);
  EXPECT_EQ(res.kind, proto::ProgramKind::ramp);
  EXPECT_EQ(res.end, proto::ProgramEnd::completed);
  EXPECT_EQ(res.repetitions_done, 1);
  std::vector<Gap> gaps;
  const std::vector<Sample> s = samples_until(probe(), res.t_device_s + 0.01, gaps);
  probe().stop_stream();
  ASSERT_EQ(gaps_text(gaps), "");
  // levels 0.5, 0.6, ..., 1.0 A, then back down to 0.5 A: 11 stairs of 50 ms each
  const std::vector<int> levels = {0, 1, 2, 3, 4, 5, 4, 3, 2, 1, 0};
  std::size_t first = 0;
  while (first < s.size() && s[first].i_cmd_A == 0.0) ++first;
  ASSERT_GE(s.size(), first + levels.size() * per_stair + 1)
      << "the stream ended before the ramp did";
  int wrong = 0;
  for (std::size_t k = 0; k < levels.size() * per_stair; ++k) {
    const double want = 0.5 + 0.1 * levels[k / per_stair];
    const double got = s[first + k].i_cmd_A;
    if (std::fabs(got - want) >= kLsb_A / 2 && ++wrong <= 5)
      ADD_FAILURE() << "sample " << k << " of the ramp: " << got << " A, want " << want << " A";
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(s[first + levels.size() * per_stair].i_cmd_A, 0.0)
      << "the current returns to 0 A at the end";
  // the program's end lies 0.55 s after its start, which the first ramp sample follows by less
  // than a sample period
  const double ramp_t0 = s[first].t_device_s;
  EXPECT_GE(res.t_device_s, ramp_t0 + 0.55 - period_s - 1e-9);
  EXPECT_LE(res.t_device_s, ramp_t0 + 0.55 + 1e-9);
}

using Stream = Scenario;
TEST_F(Stream, FiveKilohertzForTwoSecondsHasNoGaps) {
  // 8-byte samples: well within every transport, HID's 64 kB/s included; a device on a slow
  // link (QEMU's UART) streams them at the rate it advertises instead
  const double rate_Hz = stream_rate_at_most(probe().info(), 5000.0);
  const double period_s = 1.0 / rate_Hz;
  const StreamInfo info = probe().configure_stream(
      {.rate_Hz = rate_Hz, .channels = channel::i_meas | channel::encoder | channel::status});
  EXPECT_DOUBLE_EQ(info.period_s, period_s);
  probe().start_stream();
  std::vector<Gap> gaps;
  std::vector<Sample> s;
  while (s.size() < static_cast<std::size_t>(std::lround(2.0 * rate_Hz))) {
    auto item = probe().next(5s);
    ASSERT_TRUE(item.has_value()) << "the stream stopped after " << s.size() << " samples";
    if (const Sample* x = std::get_if<Sample>(&*item))
      s.push_back(*x);
    else
      gaps.push_back(std::get<Gap>(*item));
  }
  probe().stop_stream();
  EXPECT_EQ(gaps_text(gaps), "");
  int out_of_step = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    out_of_step += s[k].index != k;
    if (k > 0) out_of_step += std::fabs(s[k].t_device_s - s[k - 1].t_device_s - period_s) > 1e-9;
  }
  EXPECT_EQ(out_of_step, 0) << "indices 0, 1, 2, ... exactly one period apart";
  EXPECT_GE(s.back().t_device_s - s.front().t_device_s, 2.0 - period_s - 1e-9);
  const HealthCounters h = probe().health();
  EXPECT_EQ(h.host_samples_missing, 0u) << describe(h);
  EXPECT_EQ(h.host_queue_dropped, 0u);
  EXPECT_EQ(h.host_rx_rejected, 0u);
  EXPECT_EQ(h.stream_samples_lost, 0u);
  EXPECT_EQ(h.isr_queue_overflows, 0u);
}

using Fault = Scenario;
TEST_F(Fault, ANarrowTravelWindowTripsTravelLimitUnder1AAndClearsOnceRestored) {
  // wait for the coil to rest, so the window holds it before the current comes on
  std::int32_t c = probe().status().encoder_counts;
  for (int k = 0; k < 20; ++k) {
    std::this_thread::sleep_for(100ms);
    const std::int32_t now = probe().status().encoder_counts;
    const bool still = std::abs(now - c) <= 2;
    c = now;
    if (still) break;
  }
  Params narrow = saved_params();
  narrow.travel_min_counts = c - 500;  // 0.5 mm either side
  narrow.travel_max_counts = c + 500;
  probe().set_params(narrow);
  ASSERT_EQ(probe().fault().reason, proto::FaultReason::none) << "tripped at rest";
  HoldProgram h;
  h.current_A = 1.0f;  // pushes toward +z, out of the window
  h.duration_s = 2.0f;
  try {
    probe().run(h, 30s);
    FAIL() << "a 1 A hold stayed inside a 1 mm travel window";
  } catch (const FaultError& e) {
    EXPECT_EQ(e.reason(), static_cast<std::uint16_t>(proto::FaultReason::travel_limit)) << e.what();
  }
  const Status st = probe().status();
  EXPECT_EQ(st.state, proto::DeviceState::faulted);
  EXPECT_EQ(st.fault, proto::FaultReason::travel_limit);
  EXPECT_EQ(st.i_cmd_A, 0.0) << "a fault drives the current to zero";
  probe().set_params(saved_params());
  probe().clear_fault();
  const Status after = probe().status();
  EXPECT_EQ(after.fault, proto::FaultReason::none);
  EXPECT_EQ(after.state, proto::DeviceState::idle);
}

}  // namespace
}  // namespace palp::hil
