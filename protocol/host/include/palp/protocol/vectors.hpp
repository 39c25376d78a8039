// SPDX-License-Identifier: Apache-2.0
// Golden vectors (protocol/vectors/, format in SPEC.md §11): generated from the examples by
// `palp-proto vectors`, checked by the host tests and the firmware-side tests.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "palp/protocol/frame.hpp"

namespace palp::proto {

/// One record of a vectors file.
struct VectorRecord {
  std::string name;
  std::string about;                 // malformed.txt: how the bytes were made
  std::string expect;                // malformed.txt: the reject reason name, or "ok"
  std::string header;                // messages.txt: the "header ..." line's text after "header "
  std::vector<std::string> fields;   // messages.txt: "name = value" lines
  std::vector<u8> payload;           // messages.txt
  std::vector<u8> wire;              // both
  int line = 0;                      // line of the "vector" keyword
};

/// The text of protocol/vectors/messages.txt for this build.
std::string golden_vectors_text();
/// The text of protocol/vectors/malformed.txt for this build.
std::string malformed_vectors_text();

/// Parses a vectors file. On a syntax error returns false and sets error to "line N: problem".
bool parse_vectors(std::string_view text, std::vector<VectorRecord>& out, std::string& error);

/// What a receiver makes of some wire bytes: every accepted frame as "Name" and every reject as
/// its reason name, in order. Used to check the malformed vectors on both sides.
std::vector<std::string> receive_outcomes(const u8* wire, std::size_t size);

}  // namespace palp::proto
