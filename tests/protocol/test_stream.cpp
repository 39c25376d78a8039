// SPDX-License-Identifier: Apache-2.0
// Stream samples: layout by channel mask, scaling and the byte-rate arithmetic.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/stream.hpp"
#include "palp/protocol/multisine.hpp"
#include "palp/protocol/text.hpp"

namespace palp::proto {
namespace {

TEST(Stream, BytesPerSampleFollowTheChannelSizes) {
  EXPECT_EQ(bytes_per_sample(kAllChannels), 24u);
  EXPECT_EQ(bytes_per_sample(1u << static_cast<u8>(Channel::encoder)), 4u);
  EXPECT_EQ(bytes_per_sample(0x0006), 6u);  // i_meas + encoder
  EXPECT_EQ(bytes_per_sample(0), 0u);
  EXPECT_EQ(bytes_per_sample(0xF800), 0u);  // undefined bits carry nothing
}

TEST(Stream, ChannelsArePackedInBitOrderLittleEndian) {
  RawSample s;
  s.i_meas = -2;          // fe ff
  s.encoder = 0x01020304; // 04 03 02 01
  s.status = 0x00A5;      // a5 00
  std::vector<u8> buf(64);
  Writer w(buf.data(), buf.size());
  pack_sample(w, s, 0x0206);
  buf.resize(w.size());
  EXPECT_EQ(to_hex(buf), "fe ff 04 03 02 01 a5 00");
}

TEST(Stream, EveryMaskRoundTripsAndLeavesAbsentChannelsZero) {
  RawSample full;
  full.i_cmd = 15000;
  full.i_meas = -15000;
  full.encoder = -123456;
  full.pressure = {1, -2, 3, -4, 5, -6};
  full.status = 0xFFFF;
  full.v_cmd = -24000;
  for (u32 mask = 0; mask <= kAllChannels; mask += 37) {
    std::vector<u8> buf(64);
    Writer w(buf.data(), buf.size());
    pack_sample(w, full, static_cast<u16>(mask));
    ASSERT_EQ(w.size(), bytes_per_sample(static_cast<u16>(mask)));
    Reader r(buf.data(), w.size());
    RawSample back;
    ASSERT_TRUE(unpack_sample(r, back, static_cast<u16>(mask)));
    EXPECT_EQ(r.remaining(), 0u);
    EXPECT_EQ(back.encoder, (mask & 0x4) ? full.encoder : 0) << mask;
    EXPECT_EQ(back.pressure[5], (mask & 0x100) ? full.pressure[5] : 0) << mask;
  }
}

// Every channel takes the one-copy path (pack_sample_at): the same bytes as a store per channel.
TEST(Stream, EveryChannelPacksToTheSameBytesAsAStorePerChannel) {
  RawSample s;
  s.i_cmd = -2;
  s.i_meas = 0x0304;
  s.encoder = -123456;
  s.pressure = {1, -2, 0x1234, -4, 5, -32768};
  s.status = 0x00A5;
  s.v_cmd = 32767;
  std::array<u8, 24> fast{}, each{};
  EXPECT_EQ(pack_sample_at(fast.data(), s, kAllChannels), fast.data() + 24);
  EXPECT_EQ(detail::pack_channels(each.data(), s, kAllChannels), each.data() + 24);
  EXPECT_EQ(fast, each);
  EXPECT_EQ(to_hex(std::vector<u8>(fast.begin(), fast.begin() + 8)), "fe ff 04 03 c0 1d fe ff");
}

TEST(Stream, UnpackingPastTheEndOfTheDataFails) {
  const u8 three[] = {1, 2, 3};
  Reader r(three, sizeof three);
  RawSample s;
  EXPECT_FALSE(unpack_sample(r, s, kAllChannels));
}

TEST(Stream, FortyFullSamplesFillABatch) {
  EXPECT_EQ(max_batch_samples(kAllChannels), 40u);
  EXPECT_EQ(max_batch_samples(0x0006), 160u);
}

TEST(Stream, WireBytesOfABatchCountHeaderPayloadCrcCobsAndDelimiter) {
  // 40 x 24 = 960 data bytes; payload 22 + 960 = 982; frame 8 + 982 + 4 = 994;
  // COBS worst case 994 + 994/254 + 1 = 998; delimiter 1.
  EXPECT_EQ(batch_wire_bytes(kAllChannels, 40), 999u);
  // and the real encoding of such a batch is never longer
  const SampleBatch b = example_batch(0, 0, 40);
  std::vector<u8> out(kMaxWireFrame);
  EXPECT_LE(encode_message(b, 1, 0, out.data(), out.size()), 999u);
}

TEST(Stream, TenKilohertzOfEverythingNeedsAQuarterMegabytePerSecond) {
  EXPECT_EQ(stream_wire_bytes_per_s(kAllChannels, 10000, 40), 249750u);  // 250 x 999
  EXPECT_EQ(stream_wire_bytes_per_s(kAllChannels, 10000, 0), 0u);
}

TEST(Stream, TheExampleBatchScalesToTheIntendedPhysicalValues) {
  const SampleBatch b = example_batch(10, 20, 2);
  Reader r(b.data.items.data(), b.data.size);
  RawSample s;
  ASSERT_TRUE(unpack_sample(r, s, b.channels));
  EXPECT_NEAR(s.i_cmd * kCurrentLsb_A, 0.5, 1e-9);
  EXPECT_NEAR(s.v_cmd * kVoltageLsb_V, 2.9, 1e-9);
  EXPECT_NEAR(s.pressure[0] * kPressureLsb_Pa, -1.0, 1e-9);
}

}  // namespace
}  // namespace palp::proto

namespace palp::proto {
namespace {

TEST(BatchCheck, TheExampleBatchIsConsistent) {
  EXPECT_EQ(check_batch(example_batch(0, 0, 5)), BatchProblem::none);
}

TEST(BatchCheck, DataNotMatchingTheCountAndChannelsIsASizeMismatch) {
  SampleBatch b = example_batch(0, 0, 5);
  b.sample_count = 6;
  EXPECT_EQ(check_batch(b), BatchProblem::size_mismatch);
}

TEST(BatchCheck, ChannelBitsThisBuildDoesNotKnowAreRefused) {
  SampleBatch b = example_batch(0, 0, 5);
  b.channels = static_cast<u16>(b.channels | 0x0800);
  EXPECT_EQ(check_batch(b), BatchProblem::unknown_channels);
  EXPECT_STREQ(batch_problem_name(check_batch(b)), "unknown_channels");
}

TEST(BatchCheck, AZeroPeriodIsRefused) {
  SampleBatch b = example_batch(0, 0, 5);
  b.period_ns = 0;
  EXPECT_EQ(check_batch(b), BatchProblem::zero_period);
}

}  // namespace
}  // namespace palp::proto

namespace palp::proto {
namespace {

TEST(Multisine, XorshiftFollowsMarsagliasShifts) {
  // 1 -> 1 ^ 1<<13 = 0x2001; ^ >>17 = 0x2001; ^ <<5 = 0x2001 ^ 0x40020 = 0x42021
  EXPECT_EQ(xorshift32(1), 0x00042021u);
  EXPECT_EQ(xorshift32(0x00042021u), 0x04080601u);
}

TEST(Multisine, TheDefaultProgramExcitesNinetyLinesFrom2To20Hz) {
  const LoadMultisine m;
  EXPECT_EQ(multisine_line_count(m.line_first, m.line_last, m.line_step), 90u);
  EXPECT_EQ(multisine_line_count(10, 9, 1), 0u);
  EXPECT_EQ(multisine_line_count(10, 20, 0), 0u);
}

TEST(Multisine, RandomPhasesAreTheSuccessiveGeneratorOutputs) {
  EXPECT_EQ(multisine_phase_turns(PhaseMode::random_seeded, 1, 0, 90), 0x00042021u);
  EXPECT_EQ(multisine_phase_turns(PhaseMode::random_seeded, 1, 1, 90), 0x04080601u);
}

TEST(Multisine, SchroederPhasesAreMinusNTimesNMinusOneOver2KTurns) {
  // K = 4: line n+1 = 1, 2, 3, 4 at 0, -2/8, -6/8, -12/8 turns = 0, 0.75, 0.25, 0.5
  const u32 quarter = 1u << 30;
  EXPECT_EQ(multisine_phase_turns(PhaseMode::schroeder, 0, 0, 4), 0u);
  EXPECT_EQ(multisine_phase_turns(PhaseMode::schroeder, 0, 1, 4), 3 * quarter);
  EXPECT_EQ(multisine_phase_turns(PhaseMode::schroeder, 0, 2, 4), quarter);
  EXPECT_EQ(multisine_phase_turns(PhaseMode::schroeder, 0, 3, 4), 2 * quarter);
}

TEST(Multisine, ZeroPhasesAreZero) {
  EXPECT_EQ(multisine_phase_turns(PhaseMode::zero, 7, 5, 90), 0u);
}

}  // namespace
}  // namespace palp::proto
