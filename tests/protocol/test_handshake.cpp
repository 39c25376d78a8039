// SPDX-License-Identifier: Apache-2.0
// The handshake verdicts and the words a person reads for each.
#include <gtest/gtest.h>

#include <iterator>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace palp::proto {
namespace {

DeviceInfo device(u8 major, u8 minor, u32 hash) {
  DeviceInfo d = examples_device_info();
  d.protocol_major = major;
  d.protocol_minor = minor;
  d.schema_hash = hash;
  return d;
}

TEST(Verdict, SameVersionAndSchemaIsCompatible) {
  const Verdict v = judge(kThisProtocol, kThisProtocol);
  EXPECT_EQ(v.compatibility, Compatibility::compatible);
  EXPECT_EQ(v.because, IncompatibleBecause::none);
}

TEST(Verdict, DifferentMajorsAreIncompatible) {
  const Verdict v = judge({1, 4, 0x10}, {2, 0, 0x20});
  EXPECT_EQ(v.compatibility, Compatibility::incompatible);
  EXPECT_EQ(v.because, IncompatibleBecause::major_differs);
}

TEST(Verdict, UnderMajorZeroAnyMinorDifferenceIsIncompatible) {
  EXPECT_EQ(judge({0, 2, 0x10}, {0, 1, 0x20}).because, IncompatibleBecause::unstable_minor);
  EXPECT_EQ(judge({0, 1, 0x10}, {0, 2, 0x20}).because, IncompatibleBecause::unstable_minor);
}

TEST(Verdict, SameMajorMinorWithAnotherSchemaHashIsIncompatible) {
  EXPECT_EQ(judge({0, 1, 0x10}, {0, 1, 0x11}).because, IncompatibleBecause::schema_differs);
  EXPECT_EQ(judge({1, 3, 0x10}, {1, 3, 0x11}).because, IncompatibleBecause::schema_differs);
}

TEST(Verdict, AStableHostNewerThanTheDeviceIsCompatibleWithMissingFeatures) {
  const Verdict v = judge({1, 3, 0x10}, {1, 1, 0x20});
  EXPECT_EQ(v.compatibility, Compatibility::compatible_missing_features);
}

TEST(Verdict, AStableDeviceNewerThanTheHostIsCompatible) {
  EXPECT_EQ(judge({1, 1, 0x10}, {1, 3, 0x20}).compatibility, Compatibility::compatible);
}

// A catalogue as a later minor version would have it: a message and a field added in 1.2.
constexpr FieldInfo kOldFields[] = {
    {"current_A", 'S', "f32", 1, 1, "0", "NOLIM", "NOLIM", "A", ""},
    {"ramp_s", 'S', "f32", 1, 2, "0", "NOLIM", "NOLIM", "s", ""}};
constexpr FieldInfo kNewFields[] = {{"lines", 'S', "u16", 1, 2, "0", "NOLIM", "NOLIM", "", ""}};
constexpr MessageInfo kLaterCatalogue[] = {
    {MessageId::LoadHold, "LoadHold", Direction::H2D, 1, MessageId::Ack, "", kOldFields, 2},
    {MessageId::LoadMultisine, "LoadChirp", Direction::H2D, 2, MessageId::Ack, "", kNewFields, 1}};

TEST(Verdict, MissingFeaturesNameNewMessagesAndNewTrailingFields) {
  EXPECT_EQ(missing_feature_names(std::begin(kLaterCatalogue), std::end(kLaterCatalogue), 1),
            (std::vector<std::string>{"LoadHold.ramp_s", "LoadChirp"}));
  EXPECT_TRUE(
      missing_feature_names(std::begin(kLaterCatalogue), std::end(kLaterCatalogue), 2).empty());
}

TEST(Verdict, ThisBuildsCatalogueHasNothingNewerThanItsOwnMinor) {
  EXPECT_TRUE(missing_feature_names(kProtocolMinor).empty());
}

TEST(VerdictText, IncompatibleMajorNamesFirmwareBothVersionsBothHashesAndTheFix) {
  const ProtocolVersion host{1, 0, 0x0000abcd};
  const DeviceInfo d = device(2, 1, 0x12345678);
  EXPECT_EQ(
      describe_verdict(judge(host, {2, 1, 0x12345678}), host, d, {}),
      "incompatible: device SIM-0001 (board palp-sim, firmware 0.1.0, git 3f9c2a1) speaks "
      "protocol 2.1 with schema 0x12345678; this SDK speaks protocol 1.0 with schema 0x0000abcd: "
      "the major versions differ. Update the palp SDK to a release that speaks protocol 2.1, or "
      "flash firmware that speaks protocol 1.0: put the device in its bootloader (palp "
      "EnterBootloader; the controller then enumerates as the STM32 ROM DFU device) and flash it: "
      "dfu-util -a 0 -s 0x08000000:leave -D palp-firmware-protocol-1.0.bin. Until then the device "
      "answers only identify, version and enter-bootloader.");
}

TEST(VerdictText, AnOlderDeviceIsToldToFlashTheHostsProtocol) {
  const ProtocolVersion host{0, 3, 0xaaaa0000};
  const std::string text =
      describe_verdict(judge(host, {0, 2, 0xbbbb0000}), host, device(0, 2, 0xbbbb0000), {});
  EXPECT_NE(text.find("protocol 0.x makes no compatibility promise"), std::string::npos) << text;
  EXPECT_NE(text.find("Flash firmware that speaks protocol 0.3 (schema 0xaaaa0000)"),
            std::string::npos)
      << text;
}

TEST(VerdictText, AnUnreleasedBuildShowsBothHashes) {
  const ProtocolVersion host{0, 1, 0x11112222};
  const std::string text =
      describe_verdict(judge(host, {0, 1, 0x33334444}), host, device(0, 1, 0x33334444), {});
  EXPECT_NE(text.find("schema 0x33334444; this SDK speaks protocol 0.1 with schema 0x11112222"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("one side is an unreleased build"), std::string::npos) << text;
  EXPECT_NE(text.find("built from the same palp source"), std::string::npos) << text;
}

TEST(VerdictText, MissingFeaturesAreListedByName) {
  const ProtocolVersion host{1, 3, 0x1};
  const std::string text = describe_verdict(judge(host, {1, 1, 0x2}), host, device(1, 1, 0x2),
                                            {"LoadChirp", "LoadHold.ramp_s"});
  EXPECT_EQ(text.rfind("compatible with missing features: ", 0), 0u) << text;
  EXPECT_NE(text.find("The firmware lacks: LoadChirp, LoadHold.ramp_s."), std::string::npos)
      << text;
}

}  // namespace
}  // namespace palp::proto
