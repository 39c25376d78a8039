// SPDX-License-Identifier: Apache-2.0
// The board's stream rate limit (DeviceIdentity::max_stream_rate_Hz, SPEC.md §9.1): advertised
// in DeviceInfo, enforced by StreamConfigure (stream_too_fast naming decimation, the limit in
// Nak.detail), and kept by the default stream and across control-rate changes.
#include <gtest/gtest.h>

#include "controller_bench.hpp"

namespace palp::fw {
namespace {

using namespace palp::proto;
using test::Bench;

DeviceIdentity board_limited_to(std::uint32_t max_stream_rate_Hz) {
  DeviceIdentity id = Bench::identity();
  id.max_stream_rate_Hz = max_stream_rate_Hz;
  return id;
}

/// The period of the stream's samples, from the first batch of a short run.
std::uint32_t streamed_period_ns(Bench& b) {
  b.clear();
  b.send(StreamStart{}, 50);
  b.run_ticks(4000);
  b.send(StreamStop{}, 51);
  b.run_ticks(1);
  const auto batches = b.all<SampleBatch>();
  EXPECT_FALSE(batches.empty());
  return batches.empty() ? 0 : batches.front().period_ns;
}

TEST(StreamRate, DeviceInfoAdvertisesTheBoardsLimit) {
  Bench b(Bench::Start::with_session, board_limited_to(2000));
  b.send(GetDeviceInfo{}, 1);
  b.pump();
  EXPECT_EQ(b.last<DeviceInfo>().max_stream_rate_Hz, 2000u);
  EXPECT_EQ(b.c_.max_stream_rate_Hz(), 2000u);
}

TEST(StreamRate, AStreamConfigureAboveTheLimitIsStreamTooFastNamingDecimationWithTheLimitInDetail) {
  Bench b(Bench::Start::with_session, board_limited_to(2000));
  b.send(StreamConfigure{kAllChannels, 9, 40}, 1);  // 20 kHz / 9 = 2222 Hz
  b.pump();
  ASSERT_EQ(b.got_.size(), 1u);
  EXPECT_EQ(b.last_frame().name, "Nak");
  // request_id 0x30 StreamConfigure, error 10 stream_too_fast (u16 LE), field_index 1, detail 2000
  // (i32 LE)
  EXPECT_EQ(b.last_frame().payload, (std::vector<u8>{0x30, 0x0a, 0x00, 0x01, 0xd0, 0x07, 0x00, 0x00}));
  b.clear();
  b.send(StreamConfigure{kAllChannels, 10, 40}, 2);  // exactly 2000 Hz
  b.pump();
  EXPECT_EQ(b.last<StreamConfig>().period_ns, 500000u);
}

TEST(StreamRate, TheDefaultStreamOfASlowBoardRunsAtItsLimitAndNotAtTenKilohertz) {
  Bench b(Bench::Start::with_session, board_limited_to(3000));
  EXPECT_EQ(streamed_period_ns(b), 7u * 50000u);  // decimation 7: 2857 Hz, the fastest <= 3000 Hz
  Bench fast;  // the default limit keeps the catalogue's default stream: 10 kHz
  EXPECT_EQ(streamed_period_ns(fast), 2u * 50000u);
}

// 40 kHz / 13 = 3077 Hz fits a 3077 Hz limit; at 20 kHz half the decimation, 6, would be 3333 Hz
TEST(StreamRate, AControlRateChangeRoundsTheDecimationUpToStayWithinTheLimit) {
  Bench b(Bench::Start::with_session, board_limited_to(3077));
  SetParams p;
  p.control_rate_Hz = 40000;
  b.send(p, 1);
  b.send(StreamConfigure{kAllChannels, 13, 40}, 2);
  b.pump();
  ASSERT_EQ(b.last<StreamConfig>().decimation, 13u);
  p.control_rate_Hz = 20000;
  b.send(p, 3);
  b.pump();
  ASSERT_EQ(b.last<Params>().control_rate_Hz, 20000u);
  EXPECT_EQ(streamed_period_ns(b), 7u * 50000u);
}

// 20 kHz / 40000 = 0.5 Hz; at 40 kHz that would take decimation 80000: the u16 holds 65535
TEST(StreamRate, AVerySlowStreamStaysAtTheSlowestDecimationAcrossARateChangeRatherThanWrapping) {
  Bench b;
  b.send(StreamConfigure{kAllChannels, 40000, 1}, 1);
  SetParams p;
  p.control_rate_Hz = 40000;
  b.send(p, 2);
  b.send(StreamStart{}, 3);
  b.run_ticks(10);  // the first sample, at the start tick, is a whole batch
  const auto batches = b.all<SampleBatch>();
  ASSERT_FALSE(batches.empty());
  EXPECT_EQ(batches.front().period_ns, 65535u * 25000u);  // not 14464 ticks (80000 mod 65536)
}

TEST(StreamRate, ABoardCannotRaiseTheLimitAboveTwentyKilohertz) {
  Bench b(Bench::Start::with_session, board_limited_to(50000));
  SetParams p;
  p.control_rate_Hz = 40000;
  b.send(p, 1);
  b.send(GetDeviceInfo{}, 2);
  b.send(StreamConfigure{kAllChannels, 1, 40}, 3);  // 40 kHz: every tick at 40 kHz
  b.pump();
  EXPECT_EQ(b.last<DeviceInfo>().max_stream_rate_Hz, 20000u);
  const Nak n = b.last<Nak>();
  EXPECT_EQ(n.error, ErrorCode::stream_too_fast);
  EXPECT_EQ(n.field_index, 1);
  EXPECT_EQ(n.detail, 20000);
  b.clear();
  b.send(StreamConfigure{kAllChannels, 2, 40}, 4);  // every second tick: 20 kHz
  b.pump();
  EXPECT_EQ(b.last<StreamConfig>().period_ns, 50000u);
}

// The core's own limit (Streamer::kMaxRate_Hz) lets a board whose link carries it (USB
// full-speed bulk: 499 500 bytes/s for all channels, firmware/usb/README.md) stream every tick
// at the default control rate, with every sample there: indices 0, 1, 2, ... one tick apart.
TEST(StreamRate, ABoardAtTheDefaultLimitStreamsEveryTickAtTwentyKilohertzWithNoSampleMissing) {
  Bench b;
  b.send(GetDeviceInfo{}, 1);
  b.send(StreamConfigure{kAllChannels, 1, 40}, 2);
  b.pump();
  EXPECT_EQ(b.last<DeviceInfo>().max_stream_rate_Hz, 20000u);
  const StreamConfig c = b.last<StreamConfig>();
  EXPECT_EQ(c.period_ns, 50000u);
  EXPECT_EQ(c.wire_bytes_per_s, 499500u);  // SPEC.md §9.6: 999 bytes a batch, 500 batches/s
  b.clear();
  b.send(StreamStart{}, 3);
  b.run_ticks(2000);  // 100 ms
  b.send(StreamStop{}, 4);
  b.run_ticks(1);
  std::uint32_t next = 0;
  for (const SampleBatch& batch : b.all<SampleBatch>()) {
    ASSERT_EQ(batch.first_index, next);
    EXPECT_EQ(batch.period_ns, 50000u);
    next += batch.sample_count;
  }
  EXPECT_GE(next, 2000u);
  EXPECT_EQ(b.c_.health().stream_samples_lost, 0u);
  EXPECT_EQ(b.c_.health().isr_queue_overflows, 0u);
}

TEST(StreamRate, ALowerLimitSetLaterSlowsTheConfiguredStream) {
  Bench b;
  b.c_.set_identity(board_limited_to(1000));
  b.send(GetDeviceInfo{}, 1);
  b.pump();
  EXPECT_EQ(b.last<DeviceInfo>().max_stream_rate_Hz, 1000u);
  EXPECT_EQ(streamed_period_ns(b), 20u * 50000u);
}

}  // namespace
}  // namespace palp::fw
