// SPDX-License-Identifier: Apache-2.0
// The stream, thread side: configuration, decimation, batches of consecutive samples with exact
// times, and every loss reported once at the stage where it happened.
#include <gtest/gtest.h>

#include <vector>

#include "palp/fw/streamer.hpp"

namespace palp::fw {
namespace {

using proto::ErrorCode;

proto::StreamConfigure config(std::uint16_t channels, std::uint16_t decimation,
                              std::uint16_t batch) {
  proto::StreamConfigure c;
  c.channels = channels;
  c.decimation = decimation;
  c.batch_samples = batch;
  return c;
}

Streamer configured(std::uint16_t decimation, std::uint16_t batch, std::uint32_t rate = 20000) {
  Streamer s;
  proto::StreamConfig reply;
  std::uint8_t field = 255;
  EXPECT_EQ(s.configure(config(proto::kAllChannels, decimation, batch), rate, reply, field),
            ErrorCode::ok);
  return s;
}

IndexedSample sample(std::uint32_t index) {
  IndexedSample s;
  s.index = index;
  s.sample.encoder = static_cast<std::int32_t>(index);
  return s;
}

struct Sent {
  std::vector<proto::SampleBatch> batches;
  std::vector<proto::EventStreamGap> gaps;
  bool room = true;
  template <class M>
  bool operator()(const M& m) {
    if (!room) return false;
    if constexpr (std::is_same_v<M, proto::SampleBatch>) batches.push_back(m);
    else gaps.push_back(m);
    return true;
  }
};

TEST(Streamer, TenKilohertzOfAllChannelsIsAcceptedWithItsPeriodAndByteRate) {
  Streamer s;
  proto::StreamConfig reply;
  std::uint8_t field = 255;
  ASSERT_EQ(s.configure(config(proto::kAllChannels, 2, 40), 20000, reply, field), ErrorCode::ok);
  EXPECT_EQ(reply.period_ns, 100000u);
  EXPECT_EQ(reply.bytes_per_sample, 24);
  EXPECT_EQ(reply.wire_bytes_per_s, 249750u);
  ASSERT_EQ(s.configure(config(proto::kAllChannels, 4, 40), 40000, reply, field), ErrorCode::ok);
  EXPECT_EQ(reply.period_ns, 100000u);
}

TEST(Streamer, FasterThanTwentyKilohertzIsRefusedNamingDecimation) {
  Streamer s;
  proto::StreamConfig reply;
  std::uint8_t field = 255;
  EXPECT_EQ(s.configure(config(0x0006, 1, 40), 40000, reply, field), ErrorCode::stream_too_fast);
  EXPECT_EQ(field, 1);
  // every tick at 20 kHz and every second tick at 40 kHz are the limit itself
  EXPECT_EQ(s.configure(config(0x0006, 1, 40), 20000, reply, field), ErrorCode::ok);
  EXPECT_EQ(s.configure(config(0x0006, 2, 40), 40000, reply, field), ErrorCode::ok);
  // a board's lower limit is kept, a higher one is not
  EXPECT_EQ(s.configure(config(0x0006, 1, 40), 20000, reply, field, 10000),
            ErrorCode::stream_too_fast);
  EXPECT_EQ(s.configure(config(0x0006, 1, 40), 40000, reply, field, 40000),
            ErrorCode::stream_too_fast);
}

TEST(Streamer, ABatchLargerThanOneFrameIsOutOfRangeNamingBatchSamples) {
  Streamer s;
  proto::StreamConfig reply;
  std::uint8_t field = 255;
  EXPECT_EQ(s.configure(config(proto::kAllChannels, 2, 41), 20000, reply, field),
            ErrorCode::out_of_range);
  EXPECT_EQ(field, 2);
  EXPECT_EQ(s.configure(config(0, 2, 10), 20000, reply, field), ErrorCode::out_of_range);
  EXPECT_EQ(field, 0);  // no channel selected
}

TEST(Streamer, DecimationTakesEveryNthTickStartingWithTheFirst) {
  Streamer s = configured(3, 10);
  s.start(0);
  std::vector<int> due_ticks;
  std::vector<std::uint32_t> indices;
  for (int tick = 0; tick < 10; ++tick) {
    std::uint32_t index = 0;
    if (s.sample_due(index)) {
      due_ticks.push_back(tick);
      indices.push_back(index);
    }
  }
  EXPECT_EQ(due_ticks, (std::vector<int>{0, 3, 6, 9}));
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

TEST(Streamer, FullBatchesCarryConsecutiveIndicesAndExactDeviceTimes) {
  Streamer s = configured(2, 40);
  s.start(1000);  // stream starts at tick 1000 = 50 ms at 20 kHz
  for (std::uint32_t k = 0; k < 100; ++k) s.accept(sample(k));
  Sent sent;
  s.pump(sent);
  ASSERT_EQ(sent.batches.size(), 2u);
  EXPECT_EQ(sent.batches[0].first_index, 0u);
  EXPECT_EQ(sent.batches[0].first_time_us, 50000u);
  EXPECT_EQ(sent.batches[1].first_index, 40u);
  EXPECT_EQ(sent.batches[1].first_time_us, 50000u + 40 * 100);
  EXPECT_EQ(sent.batches[1].sample_count, 40);
  EXPECT_EQ(proto::check_batch(sent.batches[1]), proto::BatchProblem::none);
  EXPECT_EQ(s.backlog(), 20u);
  EXPECT_TRUE(sent.gaps.empty());
  s.pump(sent, true);
  ASSERT_EQ(sent.batches.size(), 3u);
  EXPECT_EQ(sent.batches[2].sample_count, 20);
}

TEST(Streamer, IndicesThatNeverArrivedAreOneGapAtTheIsrQueueAndTheNextSampleIsMarked) {
  Streamer s = configured(2, 40);
  s.start(0);
  for (std::uint32_t k = 0; k < 10; ++k) s.accept(sample(k));
  for (std::uint32_t k = 15; k < 60; ++k) s.accept(sample(k));
  Sent sent;
  s.pump(sent);
  ASSERT_EQ(sent.gaps.size(), 1u);
  EXPECT_EQ(sent.gaps[0].first_missing_index, 10u);
  EXPECT_EQ(sent.gaps[0].missing_count, 5u);
  EXPECT_EQ(sent.gaps[0].stage, proto::GapStage::isr_queue);
  EXPECT_EQ(sent.gaps[0].time_us, 10u * 100);
  EXPECT_EQ(s.counters().isr_queue_overflows, 5u);
  EXPECT_EQ(s.counters().stream_gaps, 1u);
  // the run before the hole goes out short; the next batch starts after it, marked
  ASSERT_EQ(sent.batches.size(), 2u);
  EXPECT_EQ(sent.batches[0].sample_count, 10);
  EXPECT_EQ(sent.batches[1].first_index, 15u);
  proto::Reader r(sent.batches[1].data.items.data(), sent.batches[1].data.size);
  proto::RawSample first;
  ASSERT_TRUE(proto::unpack_sample(r, first, sent.batches[1].channels));
  EXPECT_NE(first.status & (1u << static_cast<unsigned>(proto::StatusBit::after_gap)), 0u);
  proto::RawSample second;
  ASSERT_TRUE(proto::unpack_sample(r, second, sent.batches[1].channels));
  EXPECT_EQ(second.status & (1u << static_cast<unsigned>(proto::StatusBit::after_gap)), 0u);
}

TEST(Streamer, AHostThatDoesNotDrainFillsTheBacklogAndLosesAtTheBacklog) {
  Streamer s = configured(2, 40);
  s.start(0);
  Sent blocked;
  blocked.room = false;
  for (std::uint32_t k = 0; k < Streamer::kBacklogSamples + 10; ++k) {
    s.accept(sample(k));
    s.pump(blocked);
  }
  EXPECT_EQ(s.backlog(), Streamer::kBacklogSamples);
  EXPECT_EQ(s.counters().stream_backlog_max, Streamer::kBacklogSamples);
  EXPECT_EQ(s.counters().stream_samples_lost, 10u);
  Sent sent;
  s.pump(sent);
  ASSERT_EQ(sent.gaps.size(), 1u);  // ten losses in a row: one event
  EXPECT_EQ(sent.gaps[0].first_missing_index, Streamer::kBacklogSamples);
  EXPECT_EQ(sent.gaps[0].missing_count, 10u);
  EXPECT_EQ(sent.gaps[0].stage, proto::GapStage::stream_backlog);
  EXPECT_EQ(sent.batches.size(), Streamer::kBacklogSamples / 40);
}

TEST(Streamer, EverySampleIsSentOnceOrReportedLost) {
  Streamer s = configured(2, 37);
  s.start(0);
  Sent sent;
  std::uint32_t next = 0;
  for (int round = 0; round < 200; ++round) {
    for (int k = 0; k < 25; ++k) {
      if ((next % 97) != 13) s.accept(sample(next));  // one in 97 lost before the streamer
      ++next;
    }
    sent.room = round % 3 != 0;
    s.pump(sent);
  }
  sent.room = true;
  s.pump(sent, true);
  std::uint64_t delivered = 0, lost = 0;
  std::uint32_t expect = 0;
  for (const auto& b : sent.batches) {
    EXPECT_GE(b.first_index, expect);
    expect = b.first_index + b.sample_count;
    delivered += b.sample_count;
  }
  for (const auto& g : sent.gaps) lost += g.missing_count;
  EXPECT_EQ(delivered + lost, next);
}

}  // namespace
}  // namespace palp::fw
