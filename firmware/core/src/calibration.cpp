// SPDX-License-Identifier: Apache-2.0
#include "palp/fw/calibration.hpp"

#include "palp/protocol/crc32.hpp"
#include "palp/protocol/wire_types.hpp"

namespace palp::fw {

namespace {
using proto::Reader;
using proto::Writer;

constexpr std::size_t kCrcSize = 4;
constexpr std::uint32_t kErasedWord = 0xFFFFFFFFu;

std::uint32_t read_u32_le(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

template <class T, std::size_t N>
void write_array(Writer& w, const std::array<T, N>& values, std::size_t count) {
  for (std::size_t k = 0; k < N; ++k) w.scalar(k < count ? values[k] : T{});
}

template <class T, std::size_t N>
bool read_array(Reader& r, std::array<T, N>& values) {
  for (auto& v : values)
    if (!r.scalar(v)) return false;
  return true;
}

/// The fields shared by v1 and v2 up to offset 148: table, current sense, origin flag.
struct CommonFields {
  std::uint8_t kf_count = 0;
  std::uint8_t stroke_origin_valid = 0;
  std::array<std::int32_t, kForceConstantTableCapacity> kf_position_counts{};
  std::array<float, kForceConstantTableCapacity> kf_N_per_A{};
  float current_offset_A = 0.0f;
  float current_gain = 0.0f;
};

bool read_common(Reader& r, CommonFields& c) {
  std::uint16_t reserved = 0;
  return r.scalar(c.kf_count) && r.scalar(c.stroke_origin_valid) && r.scalar(reserved) &&
         read_array(r, c.kf_position_counts) && read_array(r, c.kf_N_per_A) &&
         r.scalar(c.current_offset_A) && r.scalar(c.current_gain);
}

/// Zeroes the table entries beyond the count, so equal tables compare equal.
template <class A>
void clear_unused(A& values, std::size_t count) {
  for (std::size_t k = count; k < values.size(); ++k) values[k] = {};
}

/// Table shape: 1..16 points, positions strictly increasing, both vectors the same length.
/// Returns the proto::Calibration field index at fault, or -1.
constexpr int kPositionsField = proto::field_index_of<&proto::Calibration::kf_position_counts>();
constexpr int kForceConstantsField = proto::field_index_of<&proto::Calibration::kf_N_per_A>();

int check_table_shape(const proto::Calibration& m) {
  if (m.kf_position_counts.size == 0) return kPositionsField;
  if (m.kf_N_per_A.size != m.kf_position_counts.size) return kForceConstantsField;
  for (std::size_t k = 1; k < m.kf_position_counts.size; ++k)
    if (m.kf_position_counts.items[k] <= m.kf_position_counts.items[k - 1]) return kPositionsField;
  return -1;
}

std::size_t expected_size(std::uint16_t layout_version) {
  switch (layout_version) {
    case 1: return kCalibrationBlockSizeV1;
    case 2: return kCalibrationBlockSizeV2;
    default: return 0;
  }
}
}  // namespace

const char* calibration_status_name(CalibrationStatus status) {
  switch (status) {
    case CalibrationStatus::ok: return "ok";
    case CalibrationStatus::blank: return "blank";
    case CalibrationStatus::truncated: return "truncated";
    case CalibrationStatus::bad_magic: return "bad_magic";
    case CalibrationStatus::bad_size: return "bad_size";
    case CalibrationStatus::bad_crc: return "bad_crc";
    case CalibrationStatus::unknown_version: return "unknown_version";
    case CalibrationStatus::invalid_values: return "invalid_values";
  }
  return "?";
}

CalibrationBlock serialize_calibration(const CalibrationData& data) {
  CalibrationBlock block{};
  Writer w(block.data(), block.size());
  const std::size_t count = data.kf_count <= kForceConstantTableCapacity
                                ? data.kf_count
                                : kForceConstantTableCapacity;
  w.scalar(kCalibrationMagic);
  w.scalar(kCalibrationLayoutVersion);
  w.scalar(static_cast<std::uint16_t>(kCalibrationBlockSizeV2));
  w.scalar(static_cast<std::uint8_t>(count));
  w.scalar(static_cast<std::uint8_t>(data.stroke_origin_valid ? 1 : 0));
  w.scalar(std::uint16_t{0});
  write_array(w, data.kf_position_counts, count);
  write_array(w, data.kf_N_per_A, count);
  w.scalar(data.current_offset_A);
  w.scalar(data.current_gain);
  write_array(w, data.pressure_offset_Pa, kCalibrationPressureChannels);
  write_array(w, data.pressure_gain, kCalibrationPressureChannels);
  w.scalar(data.spring_k_N_per_m);
  w.scalar(data.stroke_origin_counts);
  w.scalar(proto::crc32(block.data(), w.size()));
  return block;
}

CalibrationStatus check_calibration_block(std::span<const std::uint8_t> bytes,
                                          CalibrationHeader& header) {
  if (bytes.size() >= 4 && read_u32_le(bytes.data()) == kErasedWord)
    return CalibrationStatus::blank;
  Reader r(bytes.data(), bytes.size());
  if (!r.scalar(header.magic) || !r.scalar(header.layout_version) || !r.scalar(header.block_size))
    return CalibrationStatus::truncated;
  if (header.magic != kCalibrationMagic) return CalibrationStatus::bad_magic;
  if (header.block_size < kCalibrationHeaderSize + kCrcSize ||
      header.block_size > kCalibrationMaxBlockSize)
    return CalibrationStatus::bad_size;
  if (bytes.size() < header.block_size) return CalibrationStatus::truncated;
  const std::size_t covered = header.block_size - kCrcSize;
  if (proto::crc32(bytes.data(), covered) != read_u32_le(bytes.data() + covered))
    return CalibrationStatus::bad_crc;
  const std::size_t size_for_version = expected_size(header.layout_version);
  if (size_for_version == 0) return CalibrationStatus::unknown_version;
  if (header.block_size != size_for_version) return CalibrationStatus::bad_size;
  return CalibrationStatus::ok;
}

namespace {
// Copies the fields both layouts share into d; false when they cannot be valid.
template <class D>
bool take_common(const CommonFields& c, D& d) {
  if (c.kf_count == 0 || c.kf_count > kForceConstantTableCapacity || c.stroke_origin_valid > 1)
    return false;
  d.kf_count = c.kf_count;
  d.kf_position_counts = c.kf_position_counts;
  d.kf_N_per_A = c.kf_N_per_A;
  clear_unused(d.kf_position_counts, d.kf_count);
  clear_unused(d.kf_N_per_A, d.kf_count);
  d.current_offset_A = c.current_offset_A;
  d.current_gain = c.current_gain;
  d.stroke_origin_valid = c.stroke_origin_valid == 1;
  return true;
}
}  // namespace

CalibrationStatus parse_calibration_v2(std::span<const std::uint8_t> bytes, CalibrationData& out) {
  CalibrationHeader header;
  const CalibrationStatus status = check_calibration_block(bytes, header);
  if (status != CalibrationStatus::ok) return status;
  if (header.layout_version != 2) return CalibrationStatus::unknown_version;
  Reader r(bytes.data() + kCalibrationHeaderSize, header.block_size - kCalibrationHeaderSize);
  CommonFields c;
  CalibrationData d;
  if (!read_common(r, c) || !read_array(r, d.pressure_offset_Pa) ||
      !read_array(r, d.pressure_gain) || !r.scalar(d.spring_k_N_per_m) ||
      !r.scalar(d.stroke_origin_counts))
    return CalibrationStatus::truncated;  // cannot happen: the size was checked
  if (!take_common(c, d)) return CalibrationStatus::invalid_values;
  if (first_invalid_calibration_field(d) >= 0) return CalibrationStatus::invalid_values;
  out = d;
  return CalibrationStatus::ok;
}

CalibrationStatus parse_calibration_v1(std::span<const std::uint8_t> bytes,
                                       CalibrationDataV1& out) {
  CalibrationHeader header;
  const CalibrationStatus status = check_calibration_block(bytes, header);
  if (status != CalibrationStatus::ok) return status;
  if (header.layout_version != 1) return CalibrationStatus::unknown_version;
  Reader r(bytes.data() + kCalibrationHeaderSize, header.block_size - kCalibrationHeaderSize);
  CommonFields c;
  CalibrationDataV1 d;
  if (!read_common(r, c) || !read_array(r, d.pressure_offset_Pa) ||
      !r.scalar(d.spring_k_N_per_mm) || !r.scalar(d.stroke_origin_counts))
    return CalibrationStatus::truncated;  // cannot happen: the size was checked
  if (!take_common(c, d)) return CalibrationStatus::invalid_values;
  out = d;
  return CalibrationStatus::ok;
}

CalibrationData migrate_v1_to_v2(const CalibrationDataV1& v1) {
  CalibrationData d;
  d.kf_count = v1.kf_count;
  d.kf_position_counts = v1.kf_position_counts;
  d.kf_N_per_A = v1.kf_N_per_A;
  d.current_offset_A = v1.current_offset_A;
  d.current_gain = v1.current_gain;
  d.pressure_offset_Pa = v1.pressure_offset_Pa;
  d.pressure_gain = {1, 1, 1, 1, 1, 1};  // v1 applied no pressure gain
  // N/mm -> N/m. One IEEE float multiply is correctly rounded: the nearest float to the exact
  // product (0.0439f N/mm -> 43.9f N/m).
  constexpr float kMillimetresPerMetre = 1000.0f;
  d.spring_k_N_per_m = v1.spring_k_N_per_mm * kMillimetresPerMetre;
  d.stroke_origin_counts = v1.stroke_origin_counts;
  d.stroke_origin_valid = v1.stroke_origin_valid;
  return d;
}

CalibrationLoad load_calibration(std::span<const std::uint8_t> bytes) {
  CalibrationLoad result;
  CalibrationHeader header;
  result.status = check_calibration_block(bytes, header);
  if (result.status != CalibrationStatus::ok) return result;
  result.layout_version = header.layout_version;
  if (header.layout_version == 1) {
    CalibrationDataV1 v1;
    result.status = parse_calibration_v1(bytes, v1);
    if (result.status != CalibrationStatus::ok) return result;
    const CalibrationData migrated = migrate_v1_to_v2(v1);
    if (first_invalid_calibration_field(migrated) >= 0) {
      result.status = CalibrationStatus::invalid_values;
      return result;
    }
    result.data = migrated;
    return result;
  }
  CalibrationData data;
  result.status = parse_calibration_v2(bytes, data);
  if (result.status == CalibrationStatus::ok) result.data = data;
  return result;
}

proto::Calibration to_proto(const CalibrationData& data) {
  proto::Calibration m;
  m.layout_version = kCalibrationLayoutVersion;
  const std::size_t count = data.kf_count <= kForceConstantTableCapacity
                                ? data.kf_count
                                : kForceConstantTableCapacity;
  for (std::size_t k = 0; k < count; ++k) {
    m.kf_position_counts.push_back(data.kf_position_counts[k]);
    m.kf_N_per_A.push_back(data.kf_N_per_A[k]);
  }
  m.current_offset_A = data.current_offset_A;
  m.current_gain = data.current_gain;
  m.pressure_offset_Pa = data.pressure_offset_Pa;
  m.pressure_gain = data.pressure_gain;
  m.spring_k_N_per_m = data.spring_k_N_per_m;
  m.stroke_origin_counts = data.stroke_origin_counts;
  m.stroke_origin_valid = data.stroke_origin_valid ? 1 : 0;
  return m;
}

int from_proto(const proto::Calibration& message, CalibrationData& out) {
  const int out_of_range = message.first_out_of_range();  // the catalogue's ranges
  if (out_of_range >= 0) return out_of_range;
  const int shape = check_table_shape(message);
  if (shape >= 0) return shape;
  CalibrationData d;
  d.kf_count = static_cast<std::uint8_t>(message.kf_position_counts.size);
  d.kf_position_counts = {};
  d.kf_N_per_A = {};
  for (std::size_t k = 0; k < d.kf_count; ++k) {
    d.kf_position_counts[k] = message.kf_position_counts.items[k];
    d.kf_N_per_A[k] = message.kf_N_per_A.items[k];
  }
  d.current_offset_A = message.current_offset_A;
  d.current_gain = message.current_gain;
  d.pressure_offset_Pa = message.pressure_offset_Pa;
  d.pressure_gain = message.pressure_gain;
  d.spring_k_N_per_m = message.spring_k_N_per_m;
  d.stroke_origin_counts = message.stroke_origin_counts;
  d.stroke_origin_valid = message.stroke_origin_valid == 1;
  out = d;
  return -1;
}

int first_invalid_calibration_field(const CalibrationData& data) {
  if (data.kf_count == 0 || data.kf_count > kForceConstantTableCapacity) return kPositionsField;
  const proto::Calibration m = to_proto(data);
  const int out_of_range = m.first_out_of_range();
  if (out_of_range >= 0) return out_of_range;
  return check_table_shape(m);
}

float force_constant_N_per_A(const CalibrationData& data, std::int32_t stroke_position_counts) {
  const std::size_t n = data.kf_count <= kForceConstantTableCapacity
                            ? data.kf_count
                            : kForceConstantTableCapacity;
  if (n == 0) return kPaperForceConstant_N_per_A;
  if (stroke_position_counts <= data.kf_position_counts[0]) return data.kf_N_per_A[0];
  for (std::size_t k = 1; k < n; ++k) {
    const std::int32_t x1 = data.kf_position_counts[k];
    if (stroke_position_counts <= x1) {
      const std::int32_t x0 = data.kf_position_counts[k - 1];
      const float t = static_cast<float>(stroke_position_counts - x0) / static_cast<float>(x1 - x0);
      return data.kf_N_per_A[k - 1] + t * (data.kf_N_per_A[k] - data.kf_N_per_A[k - 1]);
    }
  }
  return data.kf_N_per_A[n - 1];
}

}  // namespace palp::fw
