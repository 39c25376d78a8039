// Shared by the recording sources (not installed): number text, the sidecar document in its
// written key order, CRC-32 as text.
#pragma once

#include <charconv>
#include <cstdint>
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

/// "cbf43926": 8 lowercase hex digits.
std::string crc32_hex(std::uint32_t crc);
/// The inverse of crc32_hex; nullopt unless exactly 8 hex digits.
std::optional<std::uint32_t> parse_crc32_hex(std::string_view text);

/// The sidecar as it is written, keys in the documented order (extra last). Throws ConfigError
/// as sidecar_to_json documents.
nlohmann::ordered_json sidecar_document(const Sidecar& sidecar);

/// "a string", "an object", "null", ...: a JSON value's kind for messages.
std::string json_kind(const nlohmann::json& value);

}  // namespace palp::recording_detail
