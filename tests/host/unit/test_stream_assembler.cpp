// SPDX-License-Identifier: Apache-2.0
// The stream assembler on synthetic batches with known indices: samples in SI units, every
// missing run a gap with the right source and size, the 32-bit wire index extended past its
// wrap, batches that go backwards refused, reconnect gaps sized from device time.
#include <gtest/gtest.h>

#include "palp/protocol/stream.hpp"
#include "probe/stream_assembler.hpp"

namespace {

using palp::Gap;
using palp::GapSource;
using palp::Sample;
using palp::StreamItem;
using palp::detail::StreamAssembler;
namespace proto = palp::proto;

/// A batch of n samples from wire index first at 10 kHz; sample k has encoder = first + k.
proto::SampleBatch batch(std::uint32_t first, std::uint16_t n, std::uint64_t t0_us = 0) {
  proto::SampleBatch b;
  b.first_index = first;
  b.first_time_us = t0_us;
  b.period_ns = 100000;
  b.channels = proto::kAllChannels;
  b.sample_count = n;
  proto::Writer w(b.data.items.data(), b.data.items.size());
  for (std::uint16_t k = 0; k < n; ++k) {
    proto::RawSample s;
    s.i_cmd = 5000;   // 1.0 A
    s.i_meas = -250;  // -0.05 A
    s.encoder = static_cast<std::int32_t>(first + k);
    s.pressure = {20, 0, 0, 0, 0, -40};  // 1 Pa, -2 Pa
    s.status = 3;
    s.v_cmd = 1234;  // 1.234 V
    proto::pack_sample(w, s, b.channels);
  }
  b.data.size = static_cast<std::uint16_t>(w.size());
  return b;
}

double identity(double t) { return t; }

TEST(StreamAssembler, SamplesCarryTheirIndexDeviceTimeAndSiValues) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  ASSERT_TRUE(a.batch(batch(0, 3, 1'000'000), identity, out));
  ASSERT_EQ(out.size(), 3u);
  const Sample& s = std::get<Sample>(out[2]);
  EXPECT_EQ(s.index, 2u);
  EXPECT_DOUBLE_EQ(s.t_device_s, 1.0 + 2 * 1e-4);
  EXPECT_DOUBLE_EQ(s.i_cmd_A, 1.0);
  EXPECT_DOUBLE_EQ(s.i_A, -0.05);
  EXPECT_EQ(s.encoder_counts, 2);
  EXPECT_DOUBLE_EQ(s.z_m, 2e-6);
  EXPECT_DOUBLE_EQ(s.p_Pa[0], 1.0);
  EXPECT_DOUBLE_EQ(s.p_Pa[5], -2.0);
  EXPECT_DOUBLE_EQ(s.v_cmd_V, 1.234);
  EXPECT_EQ(s.status, 3);
}

TEST(StreamAssembler, AMissingBatchWithoutADeviceEventIsATransportGap) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 10), identity, out);
  a.batch(batch(20, 10, 2000), identity, out);
  ASSERT_EQ(out.size(), 21u);
  const Gap& g = std::get<Gap>(out[10]);
  EXPECT_EQ(g.first_index, 10u);
  EXPECT_EQ(g.count, 10u);
  EXPECT_EQ(g.source, GapSource::transport);
  EXPECT_DOUBLE_EQ(g.t_device_s, 10 * 1e-4);
  EXPECT_EQ(std::get<Sample>(out[11]).index, 20u);
}

TEST(StreamAssembler, ADeviceReportedRunKeepsItsStageAndTheRestIsTransport) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 10), identity, out);
  proto::EventStreamGap e;
  e.first_missing_index = 14;
  e.missing_count = 3;
  e.stage = proto::GapStage::stream_backlog;
  a.device_gap(e);  // the device says 14..16 were lost in its backlog; 10..13 and 17..19 vanished
  a.batch(batch(20, 5, 2000), identity, out);
  std::vector<Gap> gaps;
  for (const auto& i : out)
    if (const Gap* g = std::get_if<Gap>(&i)) gaps.push_back(*g);
  ASSERT_EQ(gaps.size(), 3u);
  EXPECT_EQ(gaps[0].first_index, 10u);
  EXPECT_EQ(gaps[0].count, 4u);
  EXPECT_EQ(gaps[0].source, GapSource::transport);
  EXPECT_EQ(gaps[1].first_index, 14u);
  EXPECT_EQ(gaps[1].count, 3u);
  EXPECT_EQ(gaps[1].source, GapSource::stream_backlog);
  EXPECT_EQ(gaps[2].first_index, 17u);
  EXPECT_EQ(gaps[2].count, 3u);
  EXPECT_EQ(gaps[2].source, GapSource::transport);
}

TEST(StreamAssembler, TheWireIndexWrapsButTheSdkIndexKeepsCounting) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  // walk toward the 32-bit wrap in jumps below 2^31 (a larger jump would be ambiguous)
  a.batch(batch(0, 1), identity, out);
  a.batch(batch(0x7FFFFFF0u, 1), identity, out);
  a.batch(batch(0xC0000000u, 1), identity, out);
  a.batch(batch(0xFFFFFFFEu, 4), identity, out);  // wire FFFFFFFE, FFFFFFFF, 0, 1
  EXPECT_EQ(std::get<Sample>(out.back()).index, 0x100000001ull);
  out.clear();
  ASSERT_TRUE(a.batch(batch(2, 1), identity, out));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(std::get<Sample>(out[0]).index, 0x100000002ull);
}

TEST(StreamAssembler, ABatchThatRepeatsDeliveredIndicesIsRefusedAndCounted) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 10), identity, out);
  EXPECT_FALSE(a.batch(batch(5, 10), identity, out));
  EXPECT_EQ(out.size(), 10u);
  EXPECT_EQ(a.rejected(), 1u);
}

TEST(StreamAssembler, AMalformedBatchIsRefusedAndCounted) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  proto::SampleBatch b = batch(0, 4);
  b.sample_count = 5;  // the data holds 4
  EXPECT_FALSE(a.batch(b, identity, out));
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(a.rejected(), 1u);
}

TEST(StreamAssembler, AReconnectGapIsSizedFromDeviceTimeWhenTheClockRanOn) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 10, 0), identity, out);  // samples at 0 .. 0.9 ms; next due at 1.0 ms
  a.reconnected();
  out.clear();
  a.batch(batch(0, 10, 51'000), identity, out);  // the new stream starts at 51 ms: 500 missed
  const Gap& g = std::get<Gap>(out[0]);
  EXPECT_EQ(g.source, GapSource::reconnect);
  EXPECT_TRUE(g.count_known);
  EXPECT_EQ(g.count, 500u);
  EXPECT_EQ(std::get<Sample>(out[1]).index, 510u);
}

TEST(StreamAssembler, AReconnectToARestartedClockIsAGapOfUnknownSize) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 10, 5'000'000), identity, out);
  a.reconnected();
  out.clear();
  a.batch(batch(0, 10, 0), identity, out);
  const Gap& g = std::get<Gap>(out[0]);
  EXPECT_EQ(g.source, GapSource::reconnect);
  EXPECT_FALSE(g.count_known);
  EXPECT_EQ(g.count, 0u);
  EXPECT_EQ(std::get<Sample>(out[1]).index, 10u);
}

TEST(StreamAssembler, HostTimeComesFromTheMappingGiven) {
  StreamAssembler a;
  std::vector<StreamItem> out;
  a.batch(batch(0, 2, 2'000'000), [](double t) { return 100.0 + 0.5 * t; }, out);
  EXPECT_DOUBLE_EQ(std::get<Sample>(out[1]).t_host_s, 100.0 + 0.5 * (2.0 + 1e-4));
}

}  // namespace
