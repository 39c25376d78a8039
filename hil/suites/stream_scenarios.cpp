// SPDX-License-Identifier: Apache-2.0
// Streaming at the device's own limit: the rate it advertises (DeviceInfo.max_stream_rate_Hz),
// every channel, while a program runs. What the scenario proves is in README.md.
#include <gtest/gtest.h>

#include <cmath>

#include "bench.hpp"

namespace palp::hil {
namespace {

using namespace std::chrono_literals;

using Stream = Scenario;
TEST_F(Stream, AStaircaseStreamedAtTheAdvertisedMaxRateWithEveryChannelArrivesWholeAndExact) {
  const DeviceInfo& d = probe().info();
  const double rate_Hz = d.max_stream_rate_Hz;
  ASSERT_GT(rate_Hz, 0.0);
  ASSERT_EQ(std::fmod(d.control_rate_Hz, rate_Hz), 0.0)
      << "the advertised " << rate_Hz << " Hz does not divide the control rate "
      << d.control_rate_Hz << " Hz: no decimation streams it";
  std::uint16_t channels = channel::all;
  if (!d.has(proto::Capability::pressure))
    channels &= static_cast<std::uint16_t>(~channel::pressure);
  const StreamInfo info = probe().configure_stream({.rate_Hz = rate_Hz, .channels = channels});
  EXPECT_EQ(info.rate_Hz, rate_Hz);
  EXPECT_EQ(info.channels, channels);
  // 0.2, 0.3, 0.4, 0.3, 0.2 A for 0.4 s each: 2 s of program, 0.4 rate_Hz samples a stair
  RampProgram r;
  r.start_A = 0.2f;
  r.stop_A = 0.4f;
  r.step_A = 0.1f;
  r.dwell_s = 0.4f;
  r.repetitions = 1;
  r.unload = 1;
  r.displacement_limit_counts = 0;
  const std::vector<double> stairs_A = {0.2, 0.3, 0.4, 0.3, 0.2};
  const auto per_stair = static_cast<std::size_t>(std::lround(0.4 * rate_Hz));
  const HealthCounters before = probe().health();  // the device's counters run since boot
  probe().start_stream();
  const ProgramResult res = probe().run(r, 30s);
  EXPECT_EQ(res.end, proto::ProgramEnd::completed);
  std::vector<Gap> gaps;
  const std::vector<Sample> s = samples_until(probe(), res.t_device_s + 2.0 / rate_Hz, gaps);
  probe().stop_stream();
  ASSERT_EQ(gaps_text(gaps), "");
  ASSERT_FALSE(s.empty());

  // every sample, in order, one period apart
  int out_of_step = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    out_of_step += s[k].index != k;
    if (k > 0)
      out_of_step += std::fabs(s[k].t_device_s - s[k - 1].t_device_s - 1.0 / rate_Hz) > 1e-9;
  }
  EXPECT_EQ(out_of_step, 0) << "indices 0, 1, 2, ... exactly one period apart";

  // the program's samples: exactly the stairs, each for exactly its share, marked running
  std::size_t first = 0;
  while (first < s.size() && s[first].i_cmd_A == 0.0) ++first;
  ASSERT_GE(s.size(), first + stairs_A.size() * per_stair + 1) << "the stream ended early";
  int wrong = 0;
  for (std::size_t k = 0; k < stairs_A.size() * per_stair; ++k) {
    const Sample& x = s[first + k];
    const double want = stairs_A[k / per_stair];
    const bool running =
        (x.status >> static_cast<unsigned>(proto::StatusBit::program_running)) & 1u;
    if ((std::fabs(x.i_cmd_A - want) >= kLsb_A / 2 || !running) && ++wrong <= 5)
      ADD_FAILURE() << "sample " << k << " of the program: " << x.i_cmd_A << " A"
                    << (running ? "" : ", not marked running") << "; want " << want << " A";
  }
  EXPECT_EQ(wrong, 0);
  const Sample& after = s[first + stairs_A.size() * per_stair];
  EXPECT_EQ(after.i_cmd_A, 0.0) << "0 A right after the last stair";
  EXPECT_EQ((after.status >> static_cast<unsigned>(proto::StatusBit::program_running)) & 1u, 0u);
  // the channels carry the plant's values, not zeros: the coil moved, the current flowed
  EXPECT_NEAR(s[first + 2 * per_stair + per_stair - 1].i_A, 0.4, 0.04) << "measured at 0.4 A";
  EXPECT_NE(s[first + 3 * per_stair - 1].encoder_counts,
            s[first > 0 ? first - 1 : 0].encoder_counts);
  EXPECT_NE(s[first + per_stair - 1].v_cmd_V, 0.0);

  const HealthCounters h = probe().health();
  EXPECT_EQ(h.host_samples_missing, 0u) << describe(h);
  EXPECT_EQ(h.host_queue_dropped, 0u);
  EXPECT_EQ(h.host_rx_rejected, 0u);
  EXPECT_EQ(h.stream_samples_lost, before.stream_samples_lost);
  EXPECT_EQ(h.isr_queue_overflows, before.isr_queue_overflows);
  EXPECT_EQ(h.tx_frames_dropped, before.tx_frames_dropped);
  EXPECT_EQ(h.device_stream_gaps, before.device_stream_gaps);
  EXPECT_EQ(h.usb_in_not_drained, before.usb_in_not_drained);
  EXPECT_EQ(h.device_rx_rejected, before.device_rx_rejected);
  // control ticks the device dropped (QEMU on a loaded host cannot always keep 20 kHz; the
  // board counts the ticks it drops): no sample is lost with them, device time is the ticks'
  std::printf("[  FIGURES ] %zu samples at %.0f Hz, channels 0x%03x (%u wire bytes/s), device "
              "backlog at most %u samples, %u control ticks dropped meanwhile\n",
              s.size(), rate_Hz, channels, info.wire_bytes_per_s, h.stream_backlog_max,
              h.control_overruns - before.control_overruns);
}

}  // namespace
}  // namespace palp::hil
