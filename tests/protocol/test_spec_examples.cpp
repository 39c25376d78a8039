// SPDX-License-Identifier: Apache-2.0
// The worked examples of protocol/SPEC.md §12 read as an independent implementation reads them:
// the header line, the payload bytes of the tables, the CRC and the wire bytes of each example
// must agree with each other and with this build's encoder, so no part of an example can drift
// (issue 17, item 10: §12.3 once showed a 0.1 header and a stale CRC above 1.0 wire bytes).
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>

#include "palp/protocol/frame.hpp"
#include "palp/protocol/text.hpp"
#include "source_file.hpp"

namespace palp::proto {
namespace {

struct WorkedExample {
  std::string title;         // "12.3 Nak (...)"
  std::string header_line;   // "Header: major 1, minor 1, id 0x06 (`Nak`), flags 0x01, seq 11, ..."
  std::vector<u8> table_bytes;  // every backquoted run of hex byte pairs in its table rows
  std::string crc_line;      // "CRC 0x1234abcd. Wire (22 bytes):"
  std::vector<u8> wire;      // the fenced hex block
};

// Splits §12 of SPEC.md into its subsections and collects each one's parts.
std::vector<WorkedExample> worked_examples() {
  const std::string spec = palp::test::read_source("protocol/SPEC.md");
  const std::size_t from = spec.find("\n## 12. ");
  EXPECT_NE(from, std::string::npos) << "SPEC.md has no section 12";
  std::istringstream in(from == std::string::npos ? std::string() : spec.substr(from));
  const std::regex hex_run("`([0-9a-f]{2}( [0-9a-f]{2})*)`");
  std::vector<WorkedExample> out;
  std::string line, fenced;
  bool in_fence = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0 && line.rfind("## 12.", 0) != 0) break;  // the next section
    if (line.rfind("### 12.", 0) == 0) {
      out.push_back({line.substr(4), "", {}, "", {}});
      continue;
    }
    if (out.empty()) continue;
    WorkedExample& ex = out.back();
    if (line == "```") {
      if (in_fence) {
        const auto bytes = parse_hex(fenced);
        EXPECT_TRUE(bytes) << ex.title << ": the fenced block is not hex";
        if (bytes) ex.wire = *bytes;
      }
      in_fence = !in_fence;
      fenced.clear();
      continue;
    }
    if (in_fence) {
      fenced += line + "\n";
    } else if (line.rfind("Header: ", 0) == 0) {
      ex.header_line = line;
    } else if (line.rfind("CRC 0x", 0) == 0) {
      ex.crc_line = line;
    } else if (line.rfind("| ", 0) == 0) {
      for (std::sregex_iterator m(line.begin(), line.end(), hex_run), end; m != end; ++m) {
        const auto bytes = parse_hex((*m)[1].str());
        if (bytes) ex.table_bytes.insert(ex.table_bytes.end(), bytes->begin(), bytes->end());
      }
    }
  }
  return out;
}

TEST(SpecExamples, EveryWorkedExampleHasAHeaderAPayloadTableACrcAndWireBytes) {
  const std::vector<WorkedExample> examples = worked_examples();
  ASSERT_GE(examples.size(), 6u);
  for (const WorkedExample& ex : examples) {
    EXPECT_FALSE(ex.header_line.empty()) << ex.title;
    EXPECT_FALSE(ex.table_bytes.empty()) << ex.title;
    EXPECT_FALSE(ex.crc_line.empty()) << ex.title;
    EXPECT_FALSE(ex.wire.empty()) << ex.title;
  }
}

// Header line + table bytes, framed by this build's encoder, give the CRC and the wire bytes the
// example shows; and the version in the header is this build's.
TEST(SpecExamples, HeaderAndTableBytesEncodeToTheCrcAndWireBytesShown) {
  for (const WorkedExample& ex : worked_examples()) {
    unsigned major = 0, minor = 0, id = 0, flags = 0, seq = 0, len = 0;
    ASSERT_EQ(std::sscanf(ex.header_line.c_str(),
                          "Header: major %u, minor %u, id 0x%x (%*[^)]), flags 0x%x, seq %u, "
                          "payload_len %u.",
                          &major, &minor, &id, &flags, &seq, &len),
              6)
        << ex.title << ": " << ex.header_line;
    EXPECT_EQ(major, kProtocolMajor) << ex.title;
    EXPECT_EQ(minor, kProtocolMinor) << ex.title;
    EXPECT_EQ(len, ex.table_bytes.size()) << ex.title << ": payload_len against the table's bytes";

    const FrameHeader h{static_cast<u8>(major), static_cast<u8>(minor), static_cast<u8>(id),
                        static_cast<u8>(flags), static_cast<u16>(seq),
                        static_cast<u16>(ex.table_bytes.size())};
    std::vector<u8> wire(kMaxWireFrame);
    wire.resize(encode_frame(h, ex.table_bytes.data(), ex.table_bytes.size(), wire.data(),
                             wire.size()));
    EXPECT_EQ(to_hex(wire), to_hex(ex.wire)) << ex.title;

    std::vector<u8> raw = {h.major, h.minor, h.id, h.flags, static_cast<u8>(seq),
                           static_cast<u8>(seq >> 8), static_cast<u8>(len), static_cast<u8>(len >> 8)};
    raw.insert(raw.end(), ex.table_bytes.begin(), ex.table_bytes.end());
    char expected[64];
    std::snprintf(expected, sizeof expected, "CRC 0x%08x. Wire (%zu bytes):",
                  crc32(raw.data(), raw.size()), ex.wire.size());
    EXPECT_EQ(ex.crc_line, expected) << ex.title;
  }
}

// The reader's side: each example's wire bytes give back its header and payload.
TEST(SpecExamples, WireBytesDecodeToTheHeaderAndTableBytesShown) {
  for (const WorkedExample& ex : worked_examples()) {
    FrameReader reader;
    std::vector<Frame> frames;
    std::vector<u8> payload;
    reader.feed(
        ex.wire.data(), ex.wire.size(),
        [&](const Frame& f) {
          frames.push_back(f);
          payload.assign(f.payload, f.payload + f.header.payload_len);
        },
        [&](Reject r) { ADD_FAILURE() << ex.title << ": rejected " << reject_name(r); });
    ASSERT_EQ(frames.size(), 1u) << ex.title;
    EXPECT_EQ(to_hex(payload), to_hex(ex.table_bytes)) << ex.title;
    char id[8];
    std::snprintf(id, sizeof id, "id 0x%02X", frames[0].header.id);
    EXPECT_NE(ex.header_line.find(id), std::string::npos) << ex.title << ": " << ex.header_line;
  }
}

}  // namespace
}  // namespace palp::proto
