// SPDX-License-Identifier: Apache-2.0
// The calibration block (firmware/core/include/palp/fw/calibration.hpp): layouts, migration,
// error reporting, proto::Calibration conversion.
#include "palp/fw/calibration.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <span>

#include "palp/protocol/crc32.hpp"

namespace palp::fw {
namespace {

// A layout v1 block written by hand, byte by byte (the CRC computed independently with zlib).
constexpr std::array<std::uint8_t, 184> kV1Block = {
    0x50, 0x43, 0x41, 0x4C,  //   0 magic "PCAL"
    0x01, 0x00,              //   4 layout_version 1
    0xB8, 0x00,              //   6 block_size 184
    0x03,                    //   8 kf_count 3
    0x01,                    //   9 stroke_origin_valid 1
    0x00, 0x00,              //  10 reserved
    0x00, 0x00, 0x00, 0x00,  //  12 kf_position_counts[0] = 0
    0xE0, 0x2E, 0x00, 0x00,  //  16 kf_position_counts[1] = 12000
    0xC0, 0x5D, 0x00, 0x00,  //  20 kf_position_counts[2] = 24000
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  //  24..49
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  //  50..75
    0x8F, 0xC2, 0x75, 0x40,  //  76 kf_N_per_A[0] = 3.84f
    0x00, 0x00, 0x60, 0x40,  //  80 kf_N_per_A[1] = 3.5f
    0x83, 0xC0, 0x3A, 0x40,  //  84 kf_N_per_A[2] = 2.918f
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  //  88..113
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // 114..139
    0xCD, 0xCC, 0x4C, 0x3C,  // 140 current_offset_A 0.0125f
    0x5C, 0x8F, 0x82, 0x3F,  // 144 current_gain 1.02f
    0x00, 0x00, 0xC0, 0x3F,  // 148 pressure_offset_Pa[0] = 1.5
    0x00, 0x00, 0x10, 0xC0,  // 152 pressure_offset_Pa[1] = -2.25
    0x00, 0x00, 0x40, 0x40,  // 156 pressure_offset_Pa[2] = 3
    0x00, 0x00, 0x00, 0x00,  // 160 pressure_offset_Pa[3] = 0
    0x00, 0x00, 0x28, 0xC1,  // 164 pressure_offset_Pa[4] = -10.5
    0x00, 0x00, 0xF8, 0x40,  // 168 pressure_offset_Pa[5] = 7.75
    0x7D, 0xD0, 0x33, 0x3D,  // 172 spring_k_N_per_mm 0.0439f
    0x2E, 0xFB, 0xFF, 0xFF,  // 176 stroke_origin_counts -1234
    0xE8, 0x3D, 0x00, 0xAA,  // 180 CRC-32 0xAA003DE8
};

CalibrationData populated() {
  CalibrationData d;
  d.kf_count = 4;
  d.kf_position_counts = {-1000, 0, 12000, 24000};
  d.kf_N_per_A = {3.7f, 3.84f, 3.5f, 2.918f};
  d.current_offset_A = -0.0375f;
  d.current_gain = 0.995f;
  d.pressure_offset_Pa = {1.0f, -2.0f, 3.5f, -4.25f, 5.0f, -6.0f};
  d.pressure_gain = {1.01f, 0.99f, 1.1f, 0.9f, 2.0f, 0.5f};
  d.spring_k_N_per_m = 44.2f;
  d.stroke_origin_counts = 5678;
  d.stroke_origin_valid = true;
  return d;
}

/// Rewrites the CRC of a block of `size` bytes after a deliberate edit.
template <std::size_t N>
void refresh_crc(std::array<std::uint8_t, N>& block, std::size_t size) {
  const std::uint32_t crc = proto::crc32(block.data(), size - 4);
  for (int k = 0; k < 4; ++k) block[size - 4 + k] = static_cast<std::uint8_t>(crc >> (8 * k));
}

TEST(Calibration, DefaultsAreThePapersFlatKf2_918NPerAAndSpring43_9NPerM) {
  const CalibrationData d;
  EXPECT_EQ(d.kf_count, 1);
  EXPECT_EQ(d.kf_N_per_A[0], 2.918f);
  EXPECT_EQ(force_constant_N_per_A(d, -5000), 2.918f);
  EXPECT_EQ(force_constant_N_per_A(d, 24000), 2.918f);
  EXPECT_EQ(d.spring_k_N_per_m, 43.9f);
  EXPECT_EQ(d.current_offset_A, 0.0f);
  EXPECT_EQ(d.current_gain, 1.0f);
  for (std::size_t ch = 0; ch < 6; ++ch) {
    EXPECT_EQ(d.pressure_offset_Pa[ch], 0.0f);
    EXPECT_EQ(d.pressure_gain[ch], 1.0f);
  }
  EXPECT_FALSE(d.stroke_origin_valid);
  EXPECT_EQ(first_invalid_calibration_field(d), -1);
}

TEST(Calibration, V2BlockRoundTripsEveryValue) {
  const CalibrationData d = populated();
  const CalibrationBlock block = serialize_calibration(d);
  const CalibrationLoad load = load_calibration(block);
  EXPECT_EQ(load.status, CalibrationStatus::ok);
  EXPECT_EQ(load.layout_version, 2);
  EXPECT_EQ(load.data, d);
  // and the defaults too
  EXPECT_EQ(load_calibration(serialize_calibration(CalibrationData{})).data, CalibrationData{});
}

TEST(Calibration, V2BlockHasTheDocumentedLittleEndianLayout) {
  const CalibrationBlock b = serialize_calibration(populated());
  ASSERT_EQ(b.size(), 208u);
  EXPECT_EQ(b[0], 0x50);  // "PCAL"
  EXPECT_EQ(b[3], 0x4C);
  EXPECT_EQ(b[4], 0x02);  // layout 2
  EXPECT_EQ(b[5], 0x00);
  EXPECT_EQ(b[6], 0xD0);  // 208
  EXPECT_EQ(b[7], 0x00);
  EXPECT_EQ(b[8], 4);     // kf_count
  EXPECT_EQ(b[9], 1);     // origin valid
  // kf_position_counts[0] = -1000 = 0xFFFFFC18
  EXPECT_EQ(b[12], 0x18);
  EXPECT_EQ(b[13], 0xFC);
  EXPECT_EQ(b[15], 0xFF);
  // unused table entries are zero
  for (std::size_t k = 12 + 4 * 4; k < 76; ++k) EXPECT_EQ(b[k], 0) << k;
  // pressure_gain[4] = 2.0f = 0x40000000 at 172 + 16
  EXPECT_EQ(b[188], 0x00);
  EXPECT_EQ(b[191], 0x40);
  // spring 44.2f = 0x4230CCCD at 196
  EXPECT_EQ(b[196], 0xCD);
  EXPECT_EQ(b[197], 0xCC);
  EXPECT_EQ(b[198], 0x30);
  EXPECT_EQ(b[199], 0x42);
  // stroke origin 5678 = 0x162E at 200
  EXPECT_EQ(b[200], 0x2E);
  EXPECT_EQ(b[201], 0x16);
  const std::uint32_t crc = proto::crc32(b.data(), 204);
  EXPECT_EQ(b[204], crc & 0xFF);
  EXPECT_EQ(b[207], crc >> 24);
}

TEST(Calibration, HandBuiltV1BlockMigratesToV2KeepingEveryValueWithTheSpringInNPerM) {
  CalibrationDataV1 v1;
  ASSERT_EQ(parse_calibration_v1(kV1Block, v1), CalibrationStatus::ok);
  EXPECT_EQ(v1.spring_k_N_per_mm, 0.0439f);

  const CalibrationLoad load = load_calibration(kV1Block);
  ASSERT_EQ(load.status, CalibrationStatus::ok);
  EXPECT_EQ(load.layout_version, 1);  // migrated: the caller writes it back as v2
  const CalibrationData& d = load.data;
  EXPECT_EQ(d.kf_count, 3);
  EXPECT_EQ(d.kf_position_counts[0], 0);
  EXPECT_EQ(d.kf_position_counts[1], 12000);
  EXPECT_EQ(d.kf_position_counts[2], 24000);
  EXPECT_EQ(d.kf_N_per_A[0], 3.84f);
  EXPECT_EQ(d.kf_N_per_A[1], 3.5f);
  EXPECT_EQ(d.kf_N_per_A[2], 2.918f);
  EXPECT_EQ(d.current_offset_A, 0.0125f);
  EXPECT_EQ(d.current_gain, 1.02f);
  const std::array<float, 6> offsets{1.5f, -2.25f, 3.0f, 0.0f, -10.5f, 7.75f};
  EXPECT_EQ(d.pressure_offset_Pa, offsets);
  const std::array<float, 6> unity{1, 1, 1, 1, 1, 1};
  EXPECT_EQ(d.pressure_gain, unity);  // v1 had no gain: it was 1
  EXPECT_EQ(d.spring_k_N_per_m, 43.9f);  // 0.0439 N/mm
  EXPECT_EQ(d.stroke_origin_counts, -1234);
  EXPECT_TRUE(d.stroke_origin_valid);

  // written back as v2 and read again: nothing lost on the way
  const CalibrationLoad again = load_calibration(serialize_calibration(d));
  EXPECT_EQ(again.status, CalibrationStatus::ok);
  EXPECT_EQ(again.layout_version, 2);
  EXPECT_EQ(again.data, d);
}

TEST(Calibration, CorruptedByteGivesBadCrcAndTheDefaultsAreNotPassedOffAsCalibration) {
  CalibrationBlock b = serialize_calibration(populated());
  b[150] ^= 0x01;
  const CalibrationLoad load = load_calibration(b);
  EXPECT_EQ(load.status, CalibrationStatus::bad_crc);
  EXPECT_STREQ(calibration_status_name(load.status), "bad_crc");
  auto v1 = kV1Block;
  v1[172] ^= 0x80;
  EXPECT_EQ(load_calibration(v1).status, CalibrationStatus::bad_crc);
}

TEST(Calibration, TruncatedBlockIsReportedAsTruncated) {
  const CalibrationBlock b = serialize_calibration(populated());
  EXPECT_EQ(load_calibration(std::span(b.data(), 207)).status, CalibrationStatus::truncated);
  EXPECT_EQ(load_calibration(std::span(b.data(), 100)).status, CalibrationStatus::truncated);
  EXPECT_EQ(load_calibration(std::span(b.data(), 6)).status, CalibrationStatus::truncated);
  EXPECT_EQ(load_calibration(std::span(kV1Block.data(), 183)).status,
            CalibrationStatus::truncated);
}

TEST(Calibration, IntactBlockOfAnUnknownVersionIsReportedAsUnknownVersion) {
  CalibrationBlock b = serialize_calibration(populated());
  b[4] = 3;  // a newer firmware's layout, same size, valid CRC
  refresh_crc(b, b.size());
  EXPECT_EQ(load_calibration(b).status, CalibrationStatus::unknown_version);
  b[4] = 0;
  refresh_crc(b, b.size());
  EXPECT_EQ(load_calibration(b).status, CalibrationStatus::unknown_version);
}

TEST(Calibration, ErasedFlashIsBlankAndForeignBytesAreBadMagic) {
  std::array<std::uint8_t, 2048> erased{};
  erased.fill(0xFF);
  EXPECT_EQ(load_calibration(erased).status, CalibrationStatus::blank);
  CalibrationBlock b = serialize_calibration(populated());
  b[0] = 'X';
  EXPECT_EQ(load_calibration(b).status, CalibrationStatus::bad_magic);
}

TEST(Calibration, BlockSizeThatDoesNotMatchItsVersionIsBadSize) {
  // a v2 header claiming the v1 size, with a CRC valid over those 184 bytes
  CalibrationBlock b = serialize_calibration(populated());
  b[6] = 184;
  refresh_crc(b, 184);
  EXPECT_EQ(load_calibration(b).status, CalibrationStatus::bad_size);
  b[6] = 4;  // smaller than header + CRC
  EXPECT_EQ(load_calibration(b).status, CalibrationStatus::bad_size);
}

TEST(Calibration, IntactBlockWithAValueOutOfRangeIsInvalidValues) {
  CalibrationData d = populated();
  d.current_gain = 5.0f;  // catalogue range 0.5..2
  EXPECT_EQ(first_invalid_calibration_field(d), 4);
  EXPECT_EQ(load_calibration(serialize_calibration(d)).status, CalibrationStatus::invalid_values);
  d = populated();
  d.kf_position_counts[2] = 0;  // not increasing
  EXPECT_EQ(first_invalid_calibration_field(d), 1);
  EXPECT_EQ(load_calibration(serialize_calibration(d)).status, CalibrationStatus::invalid_values);
}

TEST(Calibration, ProtoConversionRoundTripsAndNamesTheFirstBadField) {
  const CalibrationData d = populated();
  const proto::Calibration m = to_proto(d);
  EXPECT_EQ(m.layout_version, 2);
  EXPECT_EQ(m.kf_position_counts.size, 4);
  EXPECT_EQ(m.kf_N_per_A.items[3], 2.918f);
  EXPECT_EQ(m.stroke_origin_valid, 1);
  CalibrationData back;
  EXPECT_EQ(from_proto(m, back), -1);
  EXPECT_EQ(back, d);

  proto::Calibration bad = m;
  bad.kf_N_per_A.size = 3;  // counts disagree
  CalibrationData untouched;
  EXPECT_EQ(from_proto(bad, untouched), 2);
  EXPECT_EQ(untouched, CalibrationData{});
  bad = m;
  bad.kf_position_counts.size = 0;
  bad.kf_N_per_A.size = 0;
  EXPECT_EQ(from_proto(bad, untouched), 1);  // empty table
  bad = m;
  bad.pressure_gain[2] = 20.0f;  // range 0.1..10
  EXPECT_EQ(from_proto(bad, untouched), 6);
  bad = m;
  bad.spring_k_N_per_m = -1.0f;
  EXPECT_EQ(from_proto(bad, untouched), 7);
}

TEST(Calibration, ForceConstantInterpolatesLinearlyBetweenPointsAndHoldsTheEnds) {
  CalibrationData d;
  d.kf_count = 3;
  d.kf_position_counts = {0, 12000, 24000};
  d.kf_N_per_A = {3.84f, 3.5f, 2.918f};
  EXPECT_EQ(force_constant_N_per_A(d, -100), 3.84f);
  EXPECT_EQ(force_constant_N_per_A(d, 0), 3.84f);
  EXPECT_NEAR(force_constant_N_per_A(d, 6000), 3.67f, 1e-6f);
  EXPECT_EQ(force_constant_N_per_A(d, 12000), 3.5f);
  EXPECT_NEAR(force_constant_N_per_A(d, 18000), 3.209f, 1e-6f);
  EXPECT_EQ(force_constant_N_per_A(d, 24000), 2.918f);
  EXPECT_EQ(force_constant_N_per_A(d, 30000), 2.918f);
}

}  // namespace
}  // namespace palp::fw
