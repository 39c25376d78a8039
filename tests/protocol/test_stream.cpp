// Stream samples: layout by channel mask, scaling and the byte-rate arithmetic.
#include <gtest/gtest.h>

#include <vector>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/stream.hpp"
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
