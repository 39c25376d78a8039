// SPDX-License-Identifier: Apache-2.0
// The independent decoder catches what it is there to catch: each test breaks one field of a
// copy of the firmware's descriptors (offsets from the facts sheet's tables) and checks that the
// decoder throws, or that the placement check reports the broken placement. Without these the
// descriptor tests could pass on a decoder that checks nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "palp/usb/descriptors.hpp"
#include "usb_decoder.hpp"

namespace {

namespace dec = palp::test::usbdec;

std::vector<std::uint8_t> copy_of(std::span<const std::uint8_t> s) { return {s.begin(), s.end()}; }
std::vector<std::uint8_t> configuration() { return copy_of(palp::usb::find_descriptor(2, 0, 0)); }
std::vector<std::uint8_t> ms_set() { return copy_of(palp::usb::ms_os_20_descriptor_set()); }

// MS OS 2.0 set offsets (facts §4.3): set header 0..9, configuration subset header 10..17,
// function subset header 18..25 (bFirstInterface at 22), compatible ID 26..45, registry
// property 46.. (wLength at 46, wPropertyNameLength at 50)
constexpr std::size_t kSetTotal = 8, kConfigSubsetTotal = 16, kFunctionFirstInterface = 22,
                      kFunctionSubsetLength = 24, kCompatibleIdText = 30, kPropertyLength = 46;

TEST(UsbDecoderCatches, MsSetWhoseTotalLengthIsWrong) {
  auto b = ms_set();
  ++b[kSetTotal];
  EXPECT_THROW(dec::decode_ms_os_20_set(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, MsSetWhoseSubsetLengthsDoNotAddUp) {
  auto b = ms_set();
  --b[kConfigSubsetTotal];
  EXPECT_THROW(dec::decode_ms_os_20_set(b), dec::DecodeError);
  b = ms_set();
  b[kFunctionSubsetLength] = static_cast<std::uint8_t>(b[kFunctionSubsetLength] - 2);
  EXPECT_THROW(dec::decode_ms_os_20_set(b), dec::DecodeError);
  b = ms_set();
  ++b[kPropertyLength];
  EXPECT_THROW(dec::decode_ms_os_20_set(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, WinUsbAndGuidMovedToTheHidFunction) {
  auto b = ms_set();
  b[kFunctionFirstInterface] = 1;  // the HID interface
  const dec::MsOs20Set set = dec::decode_ms_os_20_set(b);
  EXPECT_EQ(dec::interfaces_with_compatible_id(set, "WINUSB"), std::vector<int>{1});
  EXPECT_EQ(dec::interfaces_with_property(set, "DeviceInterfaceGUIDs"), std::vector<int>{1});
}

TEST(UsbDecoderCatches, CompatibleIdThatIsNotWinUsb) {
  auto b = ms_set();
  b[kCompatibleIdText] = 'X';
  const dec::MsOs20Set set = dec::decode_ms_os_20_set(b);
  EXPECT_TRUE(dec::interfaces_with_compatible_id(set, "WINUSB").empty());
}

TEST(UsbDecoderCatches, ConfigurationWhoseTotalLengthIsWrong) {
  auto b = configuration();
  ++b[2];  // wTotalLength
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
  b = configuration();
  b.push_back(0);
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, ConfigurationWithWrongCounts) {
  auto b = configuration();
  ++b[4];  // bNumInterfaces
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
  b = configuration();
  ++b[9 + 4];  // interface 0's bNumEndpoints
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, EndpointWithAWrongLengthOrAddress) {
  auto b = configuration();
  b[18] = 6;  // the first endpoint's bLength (config 9 + interface 9)
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
  b = configuration();
  b[18 + 2] = 0x80;  // bEndpointAddress: endpoint 0
  EXPECT_THROW(dec::decode_configuration(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, StringsThatAreNotUtf16LeWithoutTerminator) {
  const std::vector<std::uint8_t> odd{5, 3, 'a', 0, 'b'};
  EXPECT_THROW(dec::decode_string(odd), dec::DecodeError);
  const std::vector<std::uint8_t> nul{6, 3, 'a', 0, 0, 0};
  EXPECT_THROW(dec::decode_string(nul), dec::DecodeError);
  const std::vector<std::uint8_t> wrong_length{8, 3, 'a', 0, 'b', 0};
  EXPECT_THROW(dec::decode_string(wrong_length), dec::DecodeError);
  const std::vector<std::uint8_t> wrong_type{4, 2, 'a', 0};
  EXPECT_THROW(dec::decode_string(wrong_type), dec::DecodeError);
  EXPECT_EQ(dec::decode_string(std::vector<std::uint8_t>{6, 3, 'a', 0, 0xE9, 0}), "a\xC3\xA9");
}

TEST(UsbDecoderCatches, BosWithAWrongTotalOrCapabilityCount) {
  auto b = copy_of(palp::usb::find_descriptor(0x0F, 0, 0));
  ++b[2];
  EXPECT_THROW(dec::decode_bos(b), dec::DecodeError);
  b = copy_of(palp::usb::find_descriptor(0x0F, 0, 0));
  ++b[4];
  EXPECT_THROW(dec::decode_bos(b), dec::DecodeError);
}

TEST(UsbDecoderCatches, HidReportLogicalMaximumInTheOneByteFormReadsMinusOne) {
  const std::vector<std::uint8_t> r{0x15, 0x00, 0x25, 0xFF, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02};
  EXPECT_EQ(dec::summarise_hid_report(r).logical_max, -1);
  EXPECT_EQ(dec::summarise_hid_report(r).input_bits, 8u);
}

}  // namespace
