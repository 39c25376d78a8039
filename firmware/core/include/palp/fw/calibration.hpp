// SPDX-License-Identifier: Apache-2.0
// The calibration block: what proto::Calibration carries, as the board stores it in its own
// flash page (DESIGN.md: it survives firmware updates and is migrated, never silently reset).
//
// Every layout starts with the same 8-byte header and ends with a CRC; all fields little-endian,
// written and read field by field (no struct copies):
//     0  u32 magic          0x4C414350 ("PCAL" in byte order)
//     4  u16 layout_version
//     6  u16 block_size     bytes, header and CRC included
//     ...                   the layout's fields
//     block_size - 4: u32 CRC-32/ISO-HDLC (protocol/crc32.hpp) of bytes [0, block_size - 4)
//
// Layout v2 (current, 208 bytes; a multiple of 8 for the flash's 64-bit programming):
//     8  u8  kf_count (1..16)          9  u8 stroke_origin_valid (0/1)     10 u16 reserved (0)
//    12  i32[16] kf_position_counts    (from the stroke origin, increasing; unused entries 0)
//    76  f32[16] kf_N_per_A            (unused entries 0)
//   140  f32 current_offset_A         144 f32 current_gain
//   148  f32[6] pressure_offset_Pa    172 f32[6] pressure_gain
//   196  f32 spring_k_N_per_m         200 i32 stroke_origin_counts         204 u32 CRC
// Layout v1 (older, 184 bytes): the same up to offset 148, then
//   148  f32[6] pressure_offset_Pa    (no pressure gains: they were 1)
//   172  f32 spring_k_N_per_mm        (N/mm, not N/m)
//   176  i32 stroke_origin_counts     180 u32 CRC
// migrate_v1_to_v2() copies every value, sets the pressure gains to 1 (v1's implicit gain) and
// converts the spring from N/mm to N/m (x 1000, correctly rounded).
//
// Reading (load_calibration) reports exactly what is wrong and never substitutes defaults on its
// own: blank (erased flash), truncated, bad magic, bad size, bad CRC, unknown version or
// invalid values; the caller decides (e.g. run on defaults, flag the device, ask to recalibrate).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "palp/protocol/messages.hpp"

namespace palp::fw {

inline constexpr std::uint32_t kCalibrationMagic = 0x4C414350u;  // "PCAL"
inline constexpr std::uint16_t kCalibrationLayoutVersion = 2;    // the layout this core writes
inline constexpr std::size_t kCalibrationHeaderSize = 8;
inline constexpr std::size_t kCalibrationBlockSizeV1 = 184;
inline constexpr std::size_t kCalibrationBlockSizeV2 = 208;
/// Largest block_size accepted at all (one 2 KB flash page).
inline constexpr std::size_t kCalibrationMaxBlockSize = 2048;
inline constexpr std::size_t kForceConstantTableCapacity = 16;
inline constexpr std::size_t kCalibrationPressureChannels = 6;

/// The paper's values (§II-A, §IV-A): the defaults of an uncalibrated device.
inline constexpr float kPaperForceConstant_N_per_A = 2.918f;
inline constexpr float kPaperSpringStiffness_N_per_m = 43.9f;

/// The calibration the core uses: layout v2's content, SI units.
struct CalibrationData {
  /// Force-constant table, kf_count points; one point is a flat K_f.
  std::uint8_t kf_count = 1;
  std::array<std::int32_t, kForceConstantTableCapacity> kf_position_counts{};
  std::array<float, kForceConstantTableCapacity> kf_N_per_A{kPaperForceConstant_N_per_A};
  float current_offset_A = 0.0f;
  float current_gain = 1.0f;
  std::array<float, kCalibrationPressureChannels> pressure_offset_Pa{0, 0, 0, 0, 0, 0};
  std::array<float, kCalibrationPressureChannels> pressure_gain{1, 1, 1, 1, 1, 1};
  float spring_k_N_per_m = kPaperSpringStiffness_N_per_m;
  std::int32_t stroke_origin_counts = 0;
  bool stroke_origin_valid = false;

  bool operator==(const CalibrationData&) const = default;
};

/// Layout v1's content, in its units (read-only: the core never writes v1).
struct CalibrationDataV1 {
  std::uint8_t kf_count = 1;
  std::array<std::int32_t, kForceConstantTableCapacity> kf_position_counts{};
  std::array<float, kForceConstantTableCapacity> kf_N_per_A{};
  float current_offset_A = 0.0f;
  float current_gain = 1.0f;
  std::array<float, kCalibrationPressureChannels> pressure_offset_Pa{};
  float spring_k_N_per_mm = 0.0f;
  std::int32_t stroke_origin_counts = 0;
  bool stroke_origin_valid = false;
};

enum class CalibrationStatus : std::uint8_t {
  ok,
  blank,            // magic reads 0xFFFFFFFF: erased flash, never written
  truncated,        // fewer bytes than the header or than block_size
  bad_magic,        // not a calibration block
  bad_size,         // block_size implausible, or not the size of its layout version
  bad_crc,          // the CRC does not match: corrupted
  unknown_version,  // intact, but a layout this core does not know (e.g. newer firmware's)
  invalid_values,   // intact and known, but a value is outside its range
};
const char* calibration_status_name(CalibrationStatus status);

struct CalibrationHeader {
  std::uint32_t magic = 0;
  std::uint16_t layout_version = 0;
  std::uint16_t block_size = 0;
};

/// The result of reading a block: on ok, `data` is the calibration in the current layout and
/// `layout_version` the version found (1: migrated; write it back as v2). On any other status
/// `data` holds the defaults, for the caller to use or not.
struct CalibrationLoad {
  CalibrationStatus status = CalibrationStatus::blank;
  std::uint16_t layout_version = 0;
  CalibrationData data{};
};

using CalibrationBlock = std::array<std::uint8_t, kCalibrationBlockSizeV2>;

/// Writes `data` as a layout v2 block.
CalibrationBlock serialize_calibration(const CalibrationData& data);

/// Checks the header, sizes and CRC (not the version's fields).
CalibrationStatus check_calibration_block(std::span<const std::uint8_t> bytes,
                                          CalibrationHeader& header);
/// Parses an intact block of layout v2 / v1 (checks included).
CalibrationStatus parse_calibration_v2(std::span<const std::uint8_t> bytes, CalibrationData& out);
CalibrationStatus parse_calibration_v1(std::span<const std::uint8_t> bytes,
                                       CalibrationDataV1& out);
CalibrationData migrate_v1_to_v2(const CalibrationDataV1& v1);
/// Reads a block of any known layout and migrates it to the current one.
CalibrationLoad load_calibration(std::span<const std::uint8_t> bytes);

/// -1 when every value is within its range, else the proto::Calibration field index of the
/// first that is not (Nak.field_index with ErrorCode::calibration_invalid).
int first_invalid_calibration_field(const CalibrationData& data);

/// proto::Calibration (GetCalibration's answer); layout_version = kCalibrationLayoutVersion.
proto::Calibration to_proto(const CalibrationData& data);
/// SetCalibration: -1 and `out` filled when valid, else the first bad field index (`out`
/// untouched). layout_version is informative and not checked.
int from_proto(const proto::Calibration& message, CalibrationData& out);

/// K_f at a stroke position (counts from the stroke origin): linear between table points,
/// the end values beyond them.
float force_constant_N_per_A(const CalibrationData& data, std::int32_t stroke_position_counts);

}  // namespace palp::fw
