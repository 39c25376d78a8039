// SPDX-License-Identifier: Apache-2.0
// Consistent Overhead Byte Stuffing (SPEC.md §4.1): removes every 0x00 from a frame so that
// 0x00 can delimit frames on any byte stream. At most one byte of overhead per 254 bytes.
#pragma once

#include <cstddef>

#include "palp/protocol/wire_types.hpp"

namespace palp::proto {

/// Largest COBS encoding of n bytes (without the 0x00 delimiter).
constexpr std::size_t cobs_max_encoded(std::size_t n) { return n + n / 254 + 1; }

/// Encodes in[0, n) into out; returns the encoded size, or 0 when out is too small.
/// in and out must not overlap. The result contains no 0x00 byte.
std::size_t cobs_encode(const u8* in, std::size_t n, u8* out, std::size_t capacity);

/// Decodes in[0, n) (no delimiter) into out; returns the decoded size, or -1 when the input is
/// not valid COBS (a 0x00 byte, or a code byte pointing past the end). out may equal in.
int cobs_decode(const u8* in, std::size_t n, u8* out, std::size_t capacity);

}  // namespace palp::proto
