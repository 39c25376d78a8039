// SPDX-License-Identifier: Apache-2.0
// The protocol's golden vectors as the firmware test image holds them: one record per `vector`
// of protocol/vectors/messages.txt and malformed.txt (format: protocol/SPEC.md section 11).
// The tables themselves are generated at build time by firmware/cmake/vectors_to_header.cmake
// into palp_golden_vectors.hpp, which includes this header.
#pragma once

#include <cstddef>
#include <cstdint>

namespace palp::fw::vectors {

/// A record of messages.txt: a valid frame and the message it carries.
struct MessageVector {
  const char* name;  // e.g. "Hello.filled"
  std::uint32_t line;  // line of its `vector` keyword in messages.txt
  // the `header` line
  std::uint8_t major;
  std::uint8_t minor;
  std::uint8_t id;
  std::uint8_t flags;
  std::uint16_t seq;
  std::uint16_t payload_len;
  const std::uint8_t* payload;  // the `payload` line (nullptr when empty)
  std::size_t payload_size;
  const std::uint8_t* wire;  // the `wire` line: COBS frame and its 0x00 delimiter
  std::size_t wire_size;
};

/// A record of malformed.txt: a byte stream and what a receiver makes of it.
struct MalformedVector {
  const char* name;
  std::uint32_t line;  // line of its `vector` keyword in malformed.txt
  const char* about;
  const char* expect;  // space-separated outcomes: reject names or message names; "-" for none
  const std::uint8_t* wire;
  std::size_t wire_size;
};

}  // namespace palp::fw::vectors
