// SPDX-License-Identifier: Apache-2.0
// Frames on the wire: exact bytes, the incremental reader under any chunking, resynchronisation
// after garbage, and one typed, counted reason for every malformed frame.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/text.hpp"

namespace palp::proto {
namespace {

template <class M>
std::vector<u8> wire(const M& m, u16 seq, u8 flags = 0, u8 major = kProtocolMajor) {
  std::vector<u8> out(kMaxWireFrame);
  out.resize(encode_message(m, seq, flags, out.data(), out.size(), major));
  return out;
}

struct Collected {
  std::vector<FrameHeader> headers;
  std::vector<std::vector<u8>> payloads;
  std::vector<Reject> rejects;
};

Collected feed(FrameReader& r, const std::vector<u8>& bytes, std::size_t chunk = 0) {
  Collected c;
  auto on_frame = [&](const Frame& f) {
    c.headers.push_back(f.header);
    c.payloads.emplace_back(f.payload, f.payload + f.header.payload_len);
  };
  auto on_reject = [&](Reject x) { c.rejects.push_back(x); };
  if (chunk == 0) {
    r.feed(bytes.data(), bytes.size(), on_frame, on_reject);
  } else {
    for (std::size_t k = 0; k < bytes.size(); k += chunk)
      r.feed(bytes.data() + k, std::min(chunk, bytes.size() - k), on_frame, on_reject);
  }
  return c;
}

const Ping kPing{0x01020304u, 1'000'000u};

// Independently computed (Python: zlib.crc32 and a reference COBS encoder).
TEST(Frame, PingEncodesToTheExactWireBytes) {
  // in a protocol 1.0 header, so the known answer holds across minor versions
  std::vector<u8> w(kMaxWireFrame);
  w.resize(encode_message(kPing, 7, 0, w.data(), w.size(), 1, 0));
  EXPECT_EQ(to_hex(w),
            "02 01 02 10 02 07 02 0c 08 04 03 02 01 40 42 0f 01 01 01 01 05 e3 18 28 11 00");
}

TEST(Frame, HeaderFieldsSurviveTheTrip) {
  FrameReader r;
  const Collected c = feed(r, wire(kPing, 0xBEEF, kFlagResponse));
  ASSERT_EQ(c.headers.size(), 1u);
  EXPECT_EQ(c.headers[0],
            (FrameHeader{kProtocolMajor, kProtocolMinor, 0x10, kFlagResponse, 0xBEEF, 12}));
  EXPECT_TRUE(c.rejects.empty());
}

TEST(Frame, TheLargestMessageFitsTheLargestWireFrame) {
  SampleBatch b = example_batch(0, 0, 40);
  ASSERT_EQ(b.data.size, 960);
  const std::vector<u8> w = wire(b, 1);
  ASSERT_FALSE(w.empty());
  EXPECT_LE(w.size(), kMaxWireFrame);
  FrameReader r;
  EXPECT_EQ(feed(r, w).headers.size(), 1u);
}

TEST(Frame, EncodeRefusesAPayloadLargerThanTheMaximum) {
  std::vector<u8> payload(kMaxPayload + 1, 1);
  std::vector<u8> out(4096);
  EXPECT_EQ(encode_frame(FrameHeader{}, payload.data(), payload.size(), out.data(), out.size()),
            0u);
}

TEST(FrameReader, AcceptsTheSameFramesWhateverTheChunkSize) {
  std::vector<u8> stream;
  for (u16 k = 0; k < 20; ++k) {
    const std::vector<u8> w = (k % 2 == 0) ? wire(kPing, k) : wire(example_batch(k, k, 10), k);
    stream.insert(stream.end(), w.begin(), w.end());
  }
  for (std::size_t chunk : {1u, 2u, 3u, 7u, 64u, 1000u, 0u}) {
    FrameReader r;
    const Collected c = feed(r, stream, chunk);
    ASSERT_EQ(c.headers.size(), 20u) << "chunk " << chunk;
    for (u16 k = 0; k < 20; ++k) EXPECT_EQ(c.headers[k].seq, k);
    EXPECT_TRUE(c.rejects.empty());
    EXPECT_EQ(r.counters()[Reject::ok], 20u);
    EXPECT_EQ(r.pending(), 0u);
  }
}

TEST(FrameReader, RunsOfDelimitersAreIdleNotErrors) {
  FrameReader r;
  std::vector<u8> bytes(50, 0x00);
  const std::vector<u8> w = wire(kPing, 1);
  bytes.insert(bytes.end(), w.begin(), w.end());
  bytes.insert(bytes.end(), 50, 0x00);
  const Collected c = feed(r, bytes);
  EXPECT_EQ(c.headers.size(), 1u);
  EXPECT_EQ(r.counters().rejected(), 0u);
}

TEST(FrameReader, ResynchronisesAtTheNextDelimiterAfterGarbage) {
  std::mt19937 rng(7);
  std::vector<u8> bytes;
  for (int k = 0; k < 300; ++k) bytes.push_back(static_cast<u8>(1 + rng() % 255));
  bytes.push_back(0);
  const std::vector<u8> w = wire(kPing, 2);
  bytes.insert(bytes.end(), w.begin(), w.end());
  FrameReader r;
  const Collected c = feed(r, bytes, 5);
  ASSERT_EQ(c.headers.size(), 1u);
  EXPECT_EQ(c.headers[0].seq, 2);
  ASSERT_EQ(c.rejects.size(), 1u);
  EXPECT_EQ(r.counters().rejected(), 1u);
}

TEST(FrameReader, AFrameCutShortByALostByteIsRejectedAndTheNextOneRead) {
  std::vector<u8> first = wire(kPing, 1);
  first.erase(first.begin() + 6);  // a byte lost on the line
  const std::vector<u8> second = wire(kPing, 2);
  first.insert(first.end(), second.begin(), second.end());
  FrameReader r;
  const Collected c = feed(r, first);
  ASSERT_EQ(c.headers.size(), 1u);
  EXPECT_EQ(c.headers[0].seq, 2);
  EXPECT_EQ(c.rejects.size(), 1u);
}

TEST(FrameReader, AnOverlongRunIsRejectedOnceAsOversizeAndDoesNotBlockTheNextFrame) {
  std::vector<u8> bytes(5000, 0x41);
  bytes.push_back(0);
  const std::vector<u8> w = wire(kPing, 3);
  bytes.insert(bytes.end(), w.begin(), w.end());
  FrameReader r;
  const Collected c = feed(r, bytes, 100);
  ASSERT_EQ(c.rejects, std::vector<Reject>{Reject::oversize});
  ASSERT_EQ(c.headers.size(), 1u);
  EXPECT_EQ(r.counters()[Reject::oversize], 1u);
}

TEST(FrameReader, EveryFlippedBitInAFrameIsRejectedNeverAccepted) {
  const std::vector<u8> good = wire(filled_example<Params>(4), 9);
  for (std::size_t byte = 0; byte + 1 < good.size(); ++byte) {  // not the delimiter
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<u8> bad = good;
      bad[byte] = static_cast<u8>(bad[byte] ^ (1u << bit));
      FrameReader r;
      const Collected c = feed(r, bad);
      ASSERT_TRUE(c.headers.empty()) << "byte " << byte << " bit " << bit;
      ASSERT_GE(c.rejects.size(), 1u) << "byte " << byte << " bit " << bit;
    }
  }
}

TEST(FrameReader, AnotherMajorIsRejectedExceptForFrozenMessages) {
  FrameReader r;
  Collected c = feed(r, wire(kPing, 1, 0, kProtocolMajor + 1));
  EXPECT_TRUE(c.headers.empty());
  EXPECT_EQ(c.rejects, std::vector<Reject>{Reject::unsupported_major});

  for (u8 major : {u8{kProtocolMajor + 1}, u8{200}}) {
    c = feed(r, wire(GetDeviceInfo{}, 2, 0, major));
    ASSERT_EQ(c.headers.size(), 1u);
    EXPECT_EQ(c.headers[0].major, major);
    c = feed(r, wire(EnterBootloader{0x544F4F42u}, 3, 0, major));
    ASSERT_EQ(c.headers.size(), 1u);
  }
}

TEST(FrameReader, MessageLevelRejectsAreCountedOnceUnderTheirOwnReason) {
  std::vector<u8> stream;
  auto add = [&](u8 id, std::vector<u8> payload) {
    std::vector<u8> w(kMaxWireFrame);
    w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, id, 0, 1, 0},
                          payload.data(), payload.size(), w.data(), w.size()));
    stream.insert(stream.end(), w.begin(), w.end());
  };
  add(0xEE, {1, 2, 3});                                      // unknown id
  add(static_cast<u8>(MessageId::Ping), {1, 2, 3});          // Ping needs 12 bytes
  add(static_cast<u8>(MessageId::Ping), std::vector<u8>(12, 7));
  FrameReader r;
  std::vector<std::string> messages;
  std::vector<Reject> rejects;
  r.feed_messages(
      stream.data(), stream.size(),
      [&](const FrameHeader& h, const auto& m) {
        EXPECT_EQ(h.id, static_cast<u8>(m.kId));
        messages.emplace_back(m.kName);
      },
      [&](Reject x) { rejects.push_back(x); });
  EXPECT_EQ(messages, std::vector<std::string>{"Ping"});
  EXPECT_EQ(rejects, (std::vector<Reject>{Reject::unknown_message, Reject::short_payload}));
  EXPECT_EQ(r.counters()[Reject::ok], 1u);
  EXPECT_EQ(r.counters()[Reject::unknown_message], 1u);
  EXPECT_EQ(r.counters()[Reject::short_payload], 1u);
  EXPECT_EQ(r.counters().rejected(), 2u);
}

TEST(ParseFrame, ChecksLengthThenCrcThenPayloadLengthThenMajor) {
  Frame f{};
  u8 tiny[11] = {};
  EXPECT_EQ(parse_frame(tiny, sizeof tiny, f), Reject::truncated);
  std::vector<u8> raw = {kProtocolMajor + 1, 0, 0x10, 0, 0, 0, 5, 0, 0, 0, 0, 0};
  EXPECT_EQ(parse_frame(raw.data(), raw.size(), f), Reject::bad_crc);
  const u32 crc = crc32(raw.data(), 8);
  for (int k = 0; k < 4; ++k) raw[8 + k] = static_cast<u8>(crc >> (8 * k));
  EXPECT_EQ(parse_frame(raw.data(), raw.size(), f), Reject::length_mismatch);
  raw[6] = 0;
  const u32 crc2 = crc32(raw.data(), 8);
  for (int k = 0; k < 4; ++k) raw[8 + k] = static_cast<u8>(crc2 >> (8 * k));
  EXPECT_EQ(parse_frame(raw.data(), raw.size(), f), Reject::unsupported_major);
}

}  // namespace
}  // namespace palp::proto
