// SPDX-License-Identifier: Apache-2.0
// Why a frame or a message was rejected, and the counters that record it.
// Every malformed input is rejected with exactly one of these reasons and counted once.
#pragma once

#include <array>
#include <cstddef>

#include "palp/protocol/wire_types.hpp"

namespace palp::proto {

enum class Reject : u8 {
  ok = 0,
  bad_cobs,           ///< COBS code byte points past the end of the frame
  bad_crc,            ///< CRC-32 of header and payload does not match the trailer
  oversize,           ///< longer than the largest frame, or payload_len > kMaxPayload
  truncated,          ///< shorter than header + CRC (12 bytes)
  length_mismatch,    ///< header payload_len disagrees with the frame's length
  unsupported_major,  ///< another major version, and not a frozen message id
  unknown_message,    ///< message id not in this build's catalogue
  short_payload,      ///< payload ends inside or before a required field
  bad_field,          ///< a bounded array's count exceeds its capacity
};
inline constexpr std::size_t kRejectCount = 10;

/// Stable lower-case name of a reason, as used in the golden vectors and in error messages.
constexpr const char* reject_name(Reject r) {
  switch (r) {
    case Reject::ok: return "ok";
    case Reject::bad_cobs: return "bad_cobs";
    case Reject::bad_crc: return "bad_crc";
    case Reject::oversize: return "oversize";
    case Reject::truncated: return "truncated";
    case Reject::length_mismatch: return "length_mismatch";
    case Reject::unsupported_major: return "unsupported_major";
    case Reject::unknown_message: return "unknown_message";
    case Reject::short_payload: return "short_payload";
    case Reject::bad_field: return "bad_field";
  }
  return "invalid";
}

/// One counter per reason (index 0 counts accepted frames).
struct RejectCounters {
  std::array<u32, kRejectCount> by_reason{};
  constexpr void count(Reject r) { ++by_reason[static_cast<std::size_t>(r)]; }
  constexpr u32 operator[](Reject r) const { return by_reason[static_cast<std::size_t>(r)]; }
  constexpr u32 rejected() const {
    u32 n = 0;
    for (std::size_t k = 1; k < kRejectCount; ++k) n += by_reason[k];
    return n;
  }
};

}  // namespace palp::proto
