// SPDX-License-Identifier: Apache-2.0
// Shared by the recording sources (not installed): number text, the CSV's CRC-32, the sidecar
// document in its written key order.
#pragma once

#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"

namespace palp::recording_detail {

/// Room for any double or 64-bit integer std::to_chars writes.
inline constexpr std::size_t kNumberChars = 32;

/// The shortest text that reads back to the same double ("0.1", "1e-07", "-0").
inline std::string shortest(double v) {
  char buf[kNumberChars];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

using Crc32Tables = std::array<std::array<std::uint32_t, 256>, 8>;
constexpr Crc32Tables make_crc32_tables() {
  Crc32Tables t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
    t[0][n] = c;
  }
  for (std::size_t k = 1; k < 8; ++k)
    for (std::size_t n = 0; n < 256; ++n) t[k][n] = (t[k - 1][n] >> 8) ^ t[0][t[k - 1][n] & 0xFFu];
  return t;
}
inline constexpr Crc32Tables kCrc32Tables = make_crc32_tables();

/// CRC-32 as zlib computes it (the same CRC as palp::proto::crc32, SPEC.md §4.3), eight bytes at
/// a time ("slicing-by-8"): the byte-wise table took as long as formatting the numbers.
/// Start with kInit, feed bytes with update(), finish with final().
struct Crc32 {
  static constexpr std::uint32_t kInit = 0xFFFFFFFFu;
  static std::uint32_t update(std::uint32_t state, const char* data, std::size_t size) {
    const auto* p = reinterpret_cast<const unsigned char*>(data);
    const auto& t = kCrc32Tables;
    for (; size >= 8; size -= 8, p += 8) {
      const std::uint32_t lo = state ^ le32(p);
      const std::uint32_t hi = le32(p + 4);
      state = t[7][lo & 0xFFu] ^ t[6][(lo >> 8) & 0xFFu] ^ t[5][(lo >> 16) & 0xFFu] ^
              t[4][lo >> 24] ^ t[3][hi & 0xFFu] ^ t[2][(hi >> 8) & 0xFFu] ^
              t[1][(hi >> 16) & 0xFFu] ^ t[0][hi >> 24];
    }
    for (; size > 0; --size, ++p) state = t[0][(state ^ *p) & 0xFFu] ^ (state >> 8);
    return state;
  }
  static constexpr std::uint32_t final(std::uint32_t state) { return state ^ 0xFFFFFFFFu; }
  static std::uint32_t le32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
  }
};

/// "cbf43926": 8 lowercase hex digits.
std::string crc32_hex(std::uint32_t crc);
/// The inverse of crc32_hex; nullopt unless exactly 8 hex digits.
std::optional<std::uint32_t> parse_crc32_hex(std::string_view text);

/// The sidecar as it is written, keys in the documented order (extra last). Throws ConfigError
/// as sidecar_to_json documents.
nlohmann::ordered_json sidecar_document(const Sidecar& sidecar);

/// "a string", "an object", "null", ...: a JSON value's kind for messages.
std::string json_kind(const nlohmann::json& value);

/// A hidden name beside `final_path`, `.run.csv.tmp-<pid>-<n>`, that no other writer of this
/// process uses (the caller still creates it exclusively): where an atomic writer writes before
/// it renames. A crash leaves at most such a file, which can be deleted.
std::filesystem::path temporary_sibling(const std::filesystem::path& final_path);
/// Flushes a directory's entries (after a rename) to the disk; best effort.
void sync_directory(const std::filesystem::path& dir);

/// ConfigError "<who>: column i_A has 3 values where t_s has 4" unless every column the
/// recording has is as long as t_s.
void check_column_lengths(const Recording& recording, std::string_view who);

/// "2025-01-31T14:05:09Z", now: a sidecar's and a result.json's created_utc.
std::string utc_now();

}  // namespace palp::recording_detail
