// SPDX-License-Identifier: Apache-2.0
// COBS and CRC-32 against published reference values and exhaustive round trips.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "palp/protocol/cobs.hpp"
#include "palp/protocol/crc32.hpp"

namespace palp::proto {
namespace {

std::vector<u8> encode(const std::vector<u8>& in) {
  std::vector<u8> out(cobs_max_encoded(in.size()));
  const std::size_t n = cobs_encode(in.data(), in.size(), out.data(), out.size());
  out.resize(n);
  return out;
}

std::vector<u8> bytes_1_to(int last) {
  std::vector<u8> v;
  for (int k = 1; k <= last; ++k) v.push_back(static_cast<u8>(k));
  return v;
}

TEST(Crc32, CheckValueOf123456789Is0xCBF43926) {
  const char* text = "123456789";
  EXPECT_EQ(crc32(reinterpret_cast<const u8*>(text), 9), 0xCBF43926u);
}

TEST(Crc32, EmptyInputIsZero) { EXPECT_EQ(crc32(nullptr, 0), 0u); }

TEST(Crc32, IncrementalEqualsOneShot) {
  const std::vector<u8> data = bytes_1_to(200);
  u32 s = kCrc32Init;
  s = crc32_update(s, data.data(), 77);
  s = crc32_update(s, data.data() + 77, data.size() - 77);
  EXPECT_EQ(crc32_final(s), crc32(data.data(), data.size()));
}

// Slicing-by-4 (the firmware's) and slicing-by-8 (the hosts') give the byte-wise table's CRC for
// every length (the whole words and the byte tail) and every start state.
TEST(Crc32, SlicingByFourAndByEightEqualTheBytewiseTableForEveryLength) {
  std::mt19937 rng(5);
  std::vector<u8> data(300);
  for (u8& b : data) b = static_cast<u8>(rng());
  for (std::size_t n = 0; n <= data.size(); ++n) {
    for (const u32 start : {kCrc32Init, 0u, 0x12345678u}) {
      const u32 bytewise = crc32_update_bytewise(start, data.data(), n);
      ASSERT_EQ(crc32_update_sliced<4>(start, data.data(), n), bytewise) << "length " << n;
      ASSERT_EQ(crc32_update_sliced<8>(start, data.data(), n), bytewise) << "length " << n;
    }
  }
  // unaligned starts: the word loads must not assume alignment
  for (std::size_t off = 1; off < 4; ++off)
    ASSERT_EQ(crc32_update_sliced<4>(kCrc32Init, data.data() + off, 100),
              crc32_update_bytewise(kCrc32Init, data.data() + off, 100));
  constexpr u8 kCheck[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  static_assert(crc32_final(crc32_update_sliced<4>(kCrc32Init, kCheck, 9)) == 0xCBF43926u);
  static_assert(crc32_final(crc32_update_sliced<8>(kCrc32Init, kCheck, 9)) == 0xCBF43926u);
}

// The examples of Cheshire & Baker's COBS paper as listed by common references.
TEST(Cobs, EncodesTheReferenceExamples) {
  EXPECT_EQ(encode({0x00}), (std::vector<u8>{0x01, 0x01}));
  EXPECT_EQ(encode({0x00, 0x00}), (std::vector<u8>{0x01, 0x01, 0x01}));
  EXPECT_EQ(encode({0x00, 0x11, 0x00}), (std::vector<u8>{0x01, 0x02, 0x11, 0x01}));
  EXPECT_EQ(encode({0x11, 0x22, 0x00, 0x33}), (std::vector<u8>{0x03, 0x11, 0x22, 0x02, 0x33}));
  EXPECT_EQ(encode({0x11, 0x22, 0x33, 0x44}), (std::vector<u8>{0x05, 0x11, 0x22, 0x33, 0x44}));
  EXPECT_EQ(encode({0x11, 0x00, 0x00, 0x00}), (std::vector<u8>{0x02, 0x11, 0x01, 0x01, 0x01}));
  EXPECT_EQ(encode({}), (std::vector<u8>{0x01}));
}

TEST(Cobs, A254ByteRunEndsWithoutAnExtraCodeByte) {
  std::vector<u8> expected = {0xFF};
  const std::vector<u8> run = bytes_1_to(254);
  expected.insert(expected.end(), run.begin(), run.end());
  EXPECT_EQ(encode(run), expected);
}

TEST(Cobs, A254ByteRunThenAZeroClosesTheFullBlockAndCodesTheZero) {
  std::vector<u8> in = bytes_1_to(254);
  in.push_back(0x00);
  std::vector<u8> expected = {0xFF};
  expected.insert(expected.end(), in.begin(), in.end() - 1);
  expected.insert(expected.end(), {0x01, 0x01});  // an empty block before and after the zero
  EXPECT_EQ(encode(in), expected);
}

TEST(Cobs, A255ByteRunSplitsIntoTwoBlocks) {
  std::vector<u8> in = bytes_1_to(255);
  in[254] = 0xFF;
  const std::vector<u8> out = encode(in);
  ASSERT_EQ(out.size(), 257u);
  EXPECT_EQ(out[0], 0xFF);
  EXPECT_EQ(out[255], 0x02);
  EXPECT_EQ(out[256], 0xFF);
}

TEST(Cobs, RoundTripsRandomDataOfEveryLengthUpTo600WithoutZeros) {
  std::mt19937 rng(12345);
  for (std::size_t len = 0; len <= 600; ++len) {
    std::vector<u8> in(len);
    for (auto& b : in) b = static_cast<u8>(rng() % 4 == 0 ? 0 : rng());
    const std::vector<u8> enc = encode(in);
    ASSERT_LE(enc.size(), cobs_max_encoded(len));
    for (u8 b : enc) ASSERT_NE(b, 0) << "length " << len;
    std::vector<u8> dec(len + 1);
    const int n = cobs_decode(enc.data(), enc.size(), dec.data(), dec.size());
    ASSERT_EQ(n, static_cast<int>(len));
    dec.resize(len);
    ASSERT_EQ(dec, in) << "length " << len;
  }
}

// The textbook encoder (a byte a step, a code byte back-patched at every zero and every 254-byte
// run), to hold the firmware's chunked one against.
std::vector<u8> textbook_encode(const std::vector<u8>& in) {
  std::vector<u8> out(1);
  std::size_t code = 0;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in[k] == 0) {
      out[code] = static_cast<u8>(out.size() - code);
      code = out.size();
      out.push_back(0);
      continue;
    }
    out.push_back(in[k]);
    if (out.size() - code == 0xFF) {
      out[code] = 0xFF;
      if (k + 1 == in.size()) return out;
      code = out.size();
      out.push_back(0);
    }
  }
  out[code] = static_cast<u8>(out.size() - code);
  return out;
}

// Zeros from every other byte to one in 500 (runs past 254 bytes, blocks filling up inside and
// across the encoder's chunks), every length up to 1100 (a whole frame).
TEST(Cobs, EqualsTheTextbookEncoderForEveryZeroDensityAndLength) {
  std::mt19937 rng(77);
  for (const unsigned one_in : {2u, 4u, 40u, 200u, 500u}) {
    for (std::size_t len = 0; len <= 1100; len += (len < 300 ? 1 : 7)) {
      std::vector<u8> in(len);
      for (auto& b : in) b = rng() % one_in == 0 ? 0 : static_cast<u8>(1 + rng() % 255);
      ASSERT_EQ(encode(in), textbook_encode(in)) << "length " << len << ", zeros 1 in " << one_in;
    }
  }
}

TEST(Cobs, DecodeRejectsACodePastTheEnd) {
  const u8 in[] = {0x05, 0x11, 0x22};
  u8 out[8];
  EXPECT_EQ(cobs_decode(in, sizeof in, out, sizeof out), -1);
}

TEST(Cobs, DecodeRejectsAZeroByte) {
  const u8 in[] = {0x03, 0x11, 0x00};
  u8 out[8];
  EXPECT_EQ(cobs_decode(in, sizeof in, out, sizeof out), -1);
}

TEST(Cobs, DecodeRefusesToWritePastItsOutput) {
  const u8 in[] = {0x05, 0x11, 0x22, 0x33, 0x44};
  u8 out[3];
  EXPECT_EQ(cobs_decode(in, sizeof in, out, sizeof out), -1);
}

TEST(Cobs, EncodeRefusesASmallOutputBuffer) {
  const std::vector<u8> in = bytes_1_to(10);
  u8 out[10];
  EXPECT_EQ(cobs_encode(in.data(), in.size(), out, sizeof out), 0u);
}

}  // namespace
}  // namespace palp::proto
