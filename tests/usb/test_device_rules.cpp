// SPDX-License-Identifier: Apache-2.0
// The device core's hardware-free rules (requests.hpp, byte_ring.hpp), with known answers.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "palp/usb/byte_ring.hpp"
#include "palp/usb/requests.hpp"

namespace palp::usb {
namespace {

TEST(UsbSetupPacket, DecodesTheEightBytesLittleEndian) {
  // GET_DESCRIPTOR(STRING 3, LANGID 0x0409, 255): 80 06 03 03 09 04 ff 00
  const std::uint8_t bytes[8] = {0x80, 0x06, 0x03, 0x03, 0x09, 0x04, 0xFF, 0x00};
  const SetupPacket s = parse_setup(bytes);
  EXPECT_EQ(s.bmRequestType, 0x80);
  EXPECT_EQ(s.bRequest, 0x06);
  EXPECT_EQ(s.wValue, 0x0303);
  EXPECT_EQ(s.wIndex, 0x0409);
  EXPECT_EQ(s.wLength, 255);
}

TEST(UsbControlZlpRule, ZeroLengthPacketOnlyForShortRepliesThatAreWholePackets) {
  EXPECT_TRUE(control_in_needs_zlp(64, 255));    // 64-byte configuration block, wLength 255
  EXPECT_TRUE(control_in_needs_zlp(128, 129));
  EXPECT_FALSE(control_in_needs_zlp(64, 64));    // reply == wLength: the host stops by itself
  EXPECT_FALSE(control_in_needs_zlp(18, 64));    // a short packet ends the stage
  EXPECT_FALSE(control_in_needs_zlp(178, 255));  // 64 + 64 + 50: the 50 is short
  EXPECT_FALSE(control_in_needs_zlp(0, 10));     // nothing sent is no run of full packets
}

TEST(UsbHidReportTake, FullReportWhenSixtyFourBytesAreWaiting) {
  std::vector<std::uint8_t> bytes(100, 0x11);
  EXPECT_EQ(hid_report_take(bytes.data(), bytes.size()), 64u);
  EXPECT_EQ(hid_report_take(bytes.data(), 64), 64u);
}

TEST(UsbHidReportTake, ShortReportEndsAtTheLastDelimiterNeverInsideAFrame) {
  // frame A (3 bytes + 0x00), frame B (2 bytes + 0x00), then the start of frame C
  const std::uint8_t bytes[] = {1, 2, 3, 0, 4, 5, 0, 6, 7};
  EXPECT_EQ(hid_report_take(bytes, sizeof bytes), 7u);  // up to B's delimiter, C waits
  EXPECT_EQ(hid_report_take(bytes, 4), 4u);
  EXPECT_EQ(hid_report_take(bytes, 3), 0u);  // only a frame's start: wait for its end
  EXPECT_EQ(hid_report_take(bytes, 0), 0u);
}

TEST(UsbByteRing, BytesComeOutInOrderAcrossTheWrap) {
  ByteRing<8> ring;
  const std::uint8_t a[] = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(ring.push(a, 6), 6u);
  std::uint8_t out[8] = {};
  EXPECT_EQ(ring.pop(out, 4), 4u);  // tail at 4
  const std::uint8_t b[] = {7, 8, 9, 10, 11, 12, 13};
  EXPECT_EQ(ring.push(b, 7), 6u);  // 2 waiting + 6 = full: the 7th is refused
  EXPECT_EQ(ring.room(), 0u);
  EXPECT_EQ(ring.peek(1, out, 8), 7u);  // from the second byte, without taking
  EXPECT_EQ(std::vector<std::uint8_t>(out, out + 7),
            (std::vector<std::uint8_t>{6, 7, 8, 9, 10, 11, 12}));
  EXPECT_EQ(ring.at(2), 7);
  ring.drop(3);
  EXPECT_EQ(ring.pop(out, 8), 5u);
  EXPECT_EQ(std::vector<std::uint8_t>(out, out + 5), (std::vector<std::uint8_t>{8, 9, 10, 11, 12}));
  EXPECT_EQ(ring.size(), 0u);
}

}  // namespace
}  // namespace palp::usb
