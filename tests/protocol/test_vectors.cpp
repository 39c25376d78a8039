// SPDX-License-Identifier: Apache-2.0
// The golden vectors in protocol/vectors/ and the generated blocks of protocol/SPEC.md against
// this build: files, bytes, decoded values and reject reasons.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/spec_tables.hpp"
#include "palp/protocol/text.hpp"
#include "palp/protocol/vectors.hpp"
#include "source_file.hpp"

namespace palp::proto {
namespace {

std::vector<VectorRecord> records(const std::string& relative) {
  std::vector<VectorRecord> out;
  std::string error;
  EXPECT_TRUE(parse_vectors(palp::test::read_source(relative), out, error)) << relative << ": " << error;
  return out;
}

constexpr const char* kRegenerate =
    "the catalogue or the codec changed: if that was intended, bump the protocol version and run "
    "`build/release-with-assertions/protocol/palp-proto vectors protocol/vectors`";

TEST(GoldenVectors, MessagesFileIsWhatThisBuildGenerates) {
  EXPECT_EQ(palp::test::read_source("protocol/vectors/messages.txt"), golden_vectors_text()) << kRegenerate;
}

TEST(GoldenVectors, MalformedFileIsWhatThisBuildGenerates) {
  EXPECT_EQ(palp::test::read_source("protocol/vectors/malformed.txt"), malformed_vectors_text()) << kRegenerate;
}

TEST(GoldenVectors, EveryMessageVectorDecodesToItsExampleAndReencodesToTheSameBytes) {
  const std::vector<VectorRecord> recs = records("protocol/vectors/messages.txt");
  std::size_t index = 0;
  for_each_golden([&](const std::string& label, const auto& example, u16 seq, u8 flags) {
    using M = std::decay_t<decltype(example)>;
    ASSERT_LT(index, recs.size());
    const VectorRecord& rec = recs[index++];
    ASSERT_EQ(rec.name, label);

    FrameReader reader;
    std::vector<Frame> frames;
    std::vector<u8> payload;
    reader.feed(
        rec.wire.data(), rec.wire.size(),
        [&](const Frame& f) {
          frames.push_back(f);
          payload.assign(f.payload, f.payload + f.header.payload_len);
        },
        [&](Reject r) { ADD_FAILURE() << label << ": rejected " << reject_name(r); });
    ASSERT_EQ(frames.size(), 1u) << label;
    EXPECT_EQ(frames[0].header.seq, seq) << label;
    EXPECT_EQ(frames[0].header.flags, flags) << label;
    EXPECT_EQ(frames[0].header.id, static_cast<u8>(M::kId)) << label;
    EXPECT_EQ(payload, rec.payload) << label;

    M decoded;
    ASSERT_EQ(decode_payload(payload.data(), payload.size(), decoded), Reject::ok) << label;
    EXPECT_EQ(decoded, example) << label;

    std::string fields;
    for (const std::string& f : rec.fields) fields += "field " + f + "\n";
    EXPECT_EQ(fields, format_fields(decoded, "field ")) << label;

    std::vector<u8> again(kMaxWireFrame);
    again.resize(encode_message(decoded, seq, flags, again.data(), again.size()));
    EXPECT_EQ(again, rec.wire) << label;
  });
  EXPECT_EQ(index, recs.size()) << "vectors without an example";
}

TEST(GoldenVectors, EveryMessageTypeHasAVector) {
  const std::vector<VectorRecord> recs = records("protocol/vectors/messages.txt");
  for (const MessageInfo& m : kMessages) {
    bool found = false;
    for (const VectorRecord& r : recs) found = found || r.name == std::string(m.name) + ".filled";
    EXPECT_TRUE(found) << m.name;
  }
}

TEST(MalformedVectors, EachGivesExactlyItsExpectedOutcomes) {
  const std::vector<VectorRecord> recs = records("protocol/vectors/malformed.txt");
  ASSERT_GE(recs.size(), 10u);
  for (const VectorRecord& rec : recs) {
    std::string got;
    for (const std::string& o : receive_outcomes(rec.wire.data(), rec.wire.size()))
      got += (got.empty() ? "" : " ") + o;
    EXPECT_EQ(got.empty() ? "-" : got, rec.expect) << rec.name << " (" << rec.about << ")";
  }
}

TEST(MalformedVectors, CoverEveryRejectReason) {
  std::string all;
  for (const VectorRecord& rec : records("protocol/vectors/malformed.txt")) all += rec.expect + " ";
  for (std::size_t k = 1; k < kRejectCount; ++k) {
    const std::string name = reject_name(static_cast<Reject>(k));
    EXPECT_NE(all.find(name + " "), std::string::npos) << name << " has no malformed vector";
  }
}

TEST(MalformedVectors, AValidFrameAfterEachIsStillRead) {
  std::vector<u8> ping(kMaxWireFrame);
  ping.resize(encode_message(Ping{1, 2}, 5, 0, ping.data(), ping.size()));
  for (const VectorRecord& rec : records("protocol/vectors/malformed.txt")) {
    std::vector<u8> bytes = rec.wire;
    bytes.insert(bytes.end(), ping.begin(), ping.end());
    const std::vector<std::string> out = receive_outcomes(bytes.data(), bytes.size());
    ASSERT_FALSE(out.empty()) << rec.name;
    EXPECT_EQ(out.back(), "Ping") << rec.name;
  }
}

TEST(VectorsParser, NamesTheLineOfAProblem) {
  std::vector<VectorRecord> out;
  std::string error;
  EXPECT_FALSE(parse_vectors("# ok\nvector a\nwire 01 0g\n", out, error));
  EXPECT_EQ(error, "line 3: 'wire' is not hex bytes");
  EXPECT_FALSE(parse_vectors("wire 01\n", out, error));
  EXPECT_EQ(error, "line 1: 'wire' before the first 'vector'");
  EXPECT_FALSE(parse_vectors("vector a\nbogus 1\n", out, error));
  EXPECT_EQ(error, "line 2: unknown keyword 'bogus'");
}

TEST(Spec, GeneratedBlocksMatchTheCatalogue) {
  const std::string spec = palp::test::read_source("protocol/SPEC.md");
  std::string error;
  const std::string fresh = refresh_spec(spec, error);
  ASSERT_TRUE(error.empty()) << error;
  EXPECT_NE(spec.find("<!-- BEGIN GENERATED messages -->"), std::string::npos);
  EXPECT_NE(spec.find("<!-- BEGIN GENERATED schema -->"), std::string::npos);
  EXPECT_TRUE(fresh == spec)
      << "protocol/SPEC.md is out of date: run `build/release-with-assertions/protocol/palp-proto spec --write "
         "protocol/SPEC.md`";
}

}  // namespace
}  // namespace palp::proto

namespace palp::proto {
namespace {

// The hand-written parts of SPEC.md quote wire bytes; they must be this build's bytes.
TEST(Spec, EveryFencedHexExampleIsTheWireOfAGoldenVector) {
  std::string wires;
  for (const char* file : {"protocol/vectors/messages.txt", "protocol/vectors/malformed.txt"})
    for (const VectorRecord& r : records(file)) wires += to_hex(r.wire) + "\n";
  std::istringstream spec(palp::test::read_source("protocol/SPEC.md"));
  int examples = 0;
  bool in_block = false;
  std::string line, block;
  while (std::getline(spec, line)) {
    if (line.rfind("```", 0) != 0) {
      if (in_block) block += line + "\n";
      continue;
    }
    if (!in_block) {  // an opening fence; only plain ``` blocks hold hex examples
      in_block = true;
      block.clear();
      if (line != "```") block = "not hex";
      continue;
    }
    in_block = false;
    const auto bytes = parse_hex(block);
    if (!bytes || bytes->size() < 8) continue;
    ++examples;
    EXPECT_NE(wires.find(to_hex(*bytes)), std::string::npos)
        << "SPEC.md quotes wire bytes that no golden vector has:\n" << block;
  }
  EXPECT_FALSE(in_block) << "unbalanced ``` fences in SPEC.md";
  EXPECT_GE(examples, 5);
}

TEST(Spec, NamesThisBuildsVersionAndSchemaHash) {
  char expected[128];
  std::snprintf(expected, sizeof expected,
                "This document describes **protocol %u.%u** (major %u, minor %u), schema hash "
                "`0x%08x`",
                kProtocolMajor, kProtocolMinor, kProtocolMajor, kProtocolMinor, kSchemaHash);
  EXPECT_NE(palp::test::read_source("protocol/SPEC.md").find(expected), std::string::npos) << expected;
}

}  // namespace
}  // namespace palp::proto

namespace palp::proto {
namespace {

TEST(Hex, ParsesSpacedAndUnspacedBytesInEitherCase) {
  EXPECT_EQ(parse_hex("0a FF\n10"), (std::vector<u8>{0x0a, 0xff, 0x10}));
  EXPECT_EQ(parse_hex("0aff10"), (std::vector<u8>{0x0a, 0xff, 0x10}));
  EXPECT_EQ(parse_hex(""), std::vector<u8>{});
  EXPECT_EQ(to_hex(std::vector<u8>{0x0a, 0xff}), "0a ff");
}

TEST(Hex, NamesTheCharacterThatIsNotHex) {
  std::string error;
  EXPECT_FALSE(parse_hex("01 0g", &error));
  EXPECT_EQ(error, "character 5 'g' is not a hex digit");
  EXPECT_FALSE(parse_hex("01 2 34", &error));
  EXPECT_EQ(error, "a lone hex digit at character 4");
  EXPECT_FALSE(parse_hex("01 234", &error));
  EXPECT_EQ(error, "a lone hex digit at the end");
}

}  // namespace
}  // namespace palp::proto
