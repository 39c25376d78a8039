// SPDX-License-Identifier: Apache-2.0
// The firmware's USB descriptors (firmware/usb, descriptors.hpp) read back by the independent
// decoder (usb_decoder.hpp, written from the facts sheet) and compared with known answers: the
// identity and layout of protocol/include/palp/protocol/usb.hpp and the values SPEC.md §3.1 states.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "palp/protocol/usb.hpp"
#include "palp/usb/descriptors.hpp"
#include "usb_decoder.hpp"

namespace {

namespace pu = palp::proto::usb;
namespace dec = palp::test::usbdec;
using palp::usb::find_descriptor;

constexpr std::uint16_t kEnUs = 0x0409;
// SPEC.md §3.1's known answers
constexpr char kSpecGuid[] = "{69F08DC9-9AF8-419C-B6F5-404171392868}";
constexpr char kMsOs20PlatformUuid[] = "{D8DD60DF-4589-4CC7-9CD2-659D9E648A9F}";  // facts §4.1

std::vector<std::uint8_t> get(std::uint8_t type, std::uint8_t index, std::uint16_t windex = 0) {
  const auto s = find_descriptor(type, index, windex);
  return {s.begin(), s.end()};
}
std::string string_at(std::uint8_t index) { return dec::decode_string(get(0x03, index, kEnUs)); }

TEST(UsbDescriptors, DeviceDescriptorCarriesUsbHppIdentityBcdUsb0201Class0Ep0Of64) {
  const dec::Device d = dec::decode_device(get(0x01, 0));
  EXPECT_EQ(d.bcd_usb, 0x0201);  // >= 0x0201: Windows asks for the BOS (facts §3)
  EXPECT_EQ(d.device_class, 0);
  EXPECT_EQ(d.device_subclass, 0);
  EXPECT_EQ(d.device_protocol, 0);
  EXPECT_EQ(d.max_packet0, 64);
  EXPECT_EQ(d.vendor, 0x1209);
  EXPECT_EQ(d.product, 0x0001);
  EXPECT_EQ(d.vendor, pu::kVendorId);
  EXPECT_EQ(d.product, pu::kProductId);
  EXPECT_EQ(d.bcd_device, 0x0001);  // the core reports firmware 0.1 (DeviceIdentity)
  EXPECT_TRUE(pu::bcd_device_valid(d.bcd_device));
  EXPECT_EQ(d.num_configurations, 1);
  EXPECT_EQ(string_at(d.i_manufacturer), "palp");
  EXPECT_EQ(string_at(d.i_product), "palp probe controller");
  EXPECT_EQ(d.i_serial, 3);
}

TEST(UsbDescriptors, ConfigurationIs64BytesBusPoweredWithVendorBulkAndHidInterruptInterfaces) {
  const auto bytes = get(0x02, 0);
  const dec::Configuration c = dec::decode_configuration(bytes);
  EXPECT_EQ(bytes.size(), 64u);
  EXPECT_EQ(c.total_length, 64);
  EXPECT_EQ(c.num_interfaces, 2);
  EXPECT_EQ(c.value, 1);
  EXPECT_EQ(c.attributes, 0x80);  // bus-powered, no remote wakeup
  EXPECT_EQ(c.max_power, 50);     // 100 mA
  ASSERT_EQ(c.interfaces.size(), 2u);

  const dec::Interface& v = c.interfaces[0];
  EXPECT_EQ(v.number, 0);
  EXPECT_EQ(v.number, pu::kVendorInterface);
  EXPECT_EQ(v.alternate, 0);
  EXPECT_EQ(v.interface_class, 0xFF);
  EXPECT_EQ(v.subclass, 0);
  EXPECT_EQ(v.protocol, 0);
  EXPECT_FALSE(v.hid.has_value());
  ASSERT_EQ(v.endpoints.size(), 2u);
  EXPECT_EQ(v.endpoints[0].address, 0x01);
  EXPECT_EQ(v.endpoints[1].address, 0x81);
  for (const dec::Endpoint& e : v.endpoints) {
    EXPECT_EQ(e.transfer_type, 2) << "bulk";
    EXPECT_EQ(e.max_packet, 64);
    EXPECT_EQ(e.interval, 0);
  }
  EXPECT_EQ(string_at(v.i_interface), "palp byte stream (bulk)");

  const dec::Interface& h = c.interfaces[1];
  EXPECT_EQ(h.number, 1);
  EXPECT_EQ(h.number, pu::kHidInterface);
  EXPECT_EQ(h.interface_class, 0x03);
  EXPECT_EQ(h.subclass, 0) << "not a boot device";
  EXPECT_EQ(h.protocol, 0);
  ASSERT_TRUE(h.hid.has_value());
  EXPECT_EQ(h.hid->bcd_hid, 0x0111);
  EXPECT_EQ(h.hid->country, 0);
  EXPECT_EQ(h.hid->report_type, 0x22);
  EXPECT_EQ(h.hid->report_length, get(0x22, 0, 1).size());
  ASSERT_EQ(h.endpoints.size(), 2u);
  EXPECT_EQ(h.endpoints[0].address, 0x02);
  EXPECT_EQ(h.endpoints[1].address, 0x82);
  for (const dec::Endpoint& e : h.endpoints) {
    EXPECT_EQ(e.transfer_type, 3) << "interrupt";
    EXPECT_EQ(e.max_packet, 64);
    EXPECT_EQ(e.interval, 1) << "1 ms";
  }
  EXPECT_EQ(string_at(h.i_interface), "palp byte stream (HID)");
  // the endpoints are usb.hpp's
  EXPECT_EQ(v.endpoints[0].address, pu::kBulkOutEndpoint);
  EXPECT_EQ(v.endpoints[1].address, pu::kBulkInEndpoint);
  EXPECT_EQ(h.endpoints[0].address, pu::kHidOutEndpoint);
  EXPECT_EQ(h.endpoints[1].address, pu::kHidInEndpoint);
}

TEST(UsbDescriptors, HidDescriptorAloneEqualsTheOneInsideTheConfigurationBlock) {
  const auto hid = get(0x21, 0, 1);
  const auto block = get(0x02, 0);
  ASSERT_EQ(hid.size(), 9u);
  EXPECT_TRUE(std::search(block.begin(), block.end(), hid.begin(), hid.end()) != block.end());
}

TEST(UsbDescriptors, HidReportDeclaresOneVendor64ByteInputAndOutputReportWithoutReportId) {
  const auto bytes = get(0x22, 0, 1);
  EXPECT_EQ(bytes.size(), 34u);
  const dec::HidReports r = dec::summarise_hid_report(bytes);
  EXPECT_EQ(r.usage_page, 0xFF00u);
  EXPECT_FALSE(r.report_id_declared);
  EXPECT_EQ(r.input_bits, 64u * 8u);
  EXPECT_EQ(r.output_bits, 64u * 8u);
  EXPECT_EQ(r.feature_bits, 0u);
  EXPECT_EQ(r.logical_min, 0);
  EXPECT_EQ(r.logical_max, 255) << "0..255 (the 1-byte form 0xFF would read as -1)";
  EXPECT_EQ(r.open_collections, 0);
}

TEST(UsbDescriptors, StringsAreUtf16LeUnderLangId0409) {
  EXPECT_EQ(dec::decode_langids(get(0x03, 0)), std::vector<std::uint16_t>{0x0409});
  EXPECT_EQ(get(0x03, 0), (std::vector<std::uint8_t>{0x04, 0x03, 0x09, 0x04}));  // facts §1.8
  const auto product = get(0x03, 2, kEnUs);
  ASSERT_GE(product.size(), 4u);
  EXPECT_EQ(product[2], 'p');
  EXPECT_EQ(product[3], 0x00) << "UTF-16 little-endian: low byte first";
  for (std::uint8_t index = 1; index <= 5; ++index)
    EXPECT_NO_THROW(dec::decode_string(get(0x03, index, kEnUs))) << "string " << int(index);
  // a host asking before it read the LANGID list (wIndex 0) gets the same strings
  EXPECT_EQ(get(0x03, 2, 0), product);
}

TEST(UsbDescriptors, SerialNumberIsTheUidStringSetAtBoot) {
  EXPECT_TRUE(palp::usb::set_serial_number("0032001A5734501020383438"));
  EXPECT_EQ(string_at(3), "0032001A5734501020383438");
  EXPECT_EQ(get(0x03, 3, kEnUs).size(), 2u + 2u * 24u);
  EXPECT_TRUE(palp::usb::set_serial_number("AB"));
  EXPECT_EQ(string_at(3), "AB") << "a shorter serial leaves nothing of the longer one";
}

TEST(UsbDescriptors, BadSerialNumbersAreRefusedAndServedCleaned) {
  EXPECT_FALSE(palp::usb::set_serial_number("0123456789ABCDEF0123456789"));  // 26 chars
  EXPECT_EQ(string_at(3), "0123456789ABCDEF01234567") << "its first 24 characters";
  EXPECT_FALSE(palp::usb::set_serial_number("AB\x01" "C"));
  EXPECT_EQ(string_at(3), "AB?C");
  EXPECT_FALSE(palp::usb::set_serial_number(""));
  EXPECT_EQ(string_at(3), "0");
  EXPECT_FALSE(palp::usb::set_serial_number(nullptr));
  EXPECT_EQ(string_at(3), "0");
}

TEST(UsbDescriptors, UnservedRequestsGetNothingSoTheCoreStalls) {
  EXPECT_TRUE(get(0x06, 0).empty()) << "device qualifier: full speed only";
  EXPECT_TRUE(get(0x07, 0).empty()) << "other-speed configuration";
  EXPECT_TRUE(get(0x01, 1).empty()) << "device descriptor index 1";
  EXPECT_TRUE(get(0x02, 1).empty()) << "a second configuration";
  EXPECT_TRUE(get(0x03, 6, kEnUs).empty()) << "string 6";
  EXPECT_TRUE(get(0x03, 0xEE, kEnUs).empty()) << "MS OS 1.0 string: MS OS 2.0 only (facts §1.8)";
  EXPECT_TRUE(get(0x03, 2, 0x0407).empty()) << "a language not in the LANGID list";
  EXPECT_TRUE(get(0x22, 0, 0).empty()) << "HID report asked of the vendor interface";
  EXPECT_TRUE(get(0x21, 0, 0).empty()) << "HID descriptor asked of the vendor interface";
  EXPECT_TRUE(get(0x0F, 1).empty()) << "BOS index 1";
}

TEST(UsbDescriptors, BosHoldsOnlyTheMsOs20PlatformCapabilityPointingAtTheSet) {
  const auto bytes = get(0x0F, 0);
  const dec::Bos bos = dec::decode_bos(bytes);
  EXPECT_EQ(bos.total_length, 33);  // facts §4.1: 5 + 28
  EXPECT_EQ(bos.num_capabilities, 1);
  EXPECT_EQ(bos.capability_types, std::vector<std::uint8_t>{0x05});
  ASSERT_EQ(bos.platform.size(), 1u);
  EXPECT_EQ(bos.platform[0].uuid, dec::guid_bytes(kMsOs20PlatformUuid));
  const std::array<std::uint8_t, 16> sheet_bytes{0xDF, 0x60, 0xDD, 0xD8, 0x89, 0x45, 0xC7, 0x4C,
                                                 0x9C, 0xD2, 0x65, 0x9D, 0x9E, 0x64, 0x8A, 0x9F};
  EXPECT_EQ(dec::guid_bytes(kMsOs20PlatformUuid), sheet_bytes) << "the decoder's GUID order";
  const dec::MsOs20Capability m = dec::decode_ms_os_20_capability(bos.platform[0]);
  EXPECT_EQ(m.windows_version, 0x06030000u);
  EXPECT_EQ(m.set_total_length, palp::usb::ms_os_20_descriptor_set().size());
  EXPECT_EQ(m.set_total_length, 178);
  EXPECT_EQ(m.vendor_code, palp::usb::kMsOs20VendorCode);
  EXPECT_EQ(m.vendor_code, 0x50);
  EXPECT_EQ(m.alt_enum_code, 0);
  EXPECT_EQ(palp::usb::kMsOs20DescriptorIndex, 7);
}

bool is_winusb(const dec::MsFeature& f) { return f.type == 3 && f.compatible_id == "WINUSB"; }
bool is_guid_property(const dec::MsFeature& f) {
  return f.type == 4 && dec::to_utf8(f.property_name) == "DeviceInterfaceGUIDs";
}

TEST(UsbDescriptors, MsOs20SetGivesWinUsbAndTheGuidToTheVendorInterfaceOnlyNeverTheHid) {
  const auto s = palp::usb::ms_os_20_descriptor_set();
  const dec::MsOs20Set set = dec::decode_ms_os_20_set({s.begin(), s.end()});
  EXPECT_EQ(set.windows_version, 0x06030000u);
  EXPECT_EQ(set.total_length, 178);
  EXPECT_TRUE(set.device_features.empty()) << "composite: features belong in a function subset";
  ASSERT_EQ(set.configurations.size(), 1u);
  EXPECT_EQ(set.configurations[0].configuration, 0) << "the first configuration's index";
  EXPECT_TRUE(set.configurations[0].features.empty());
  ASSERT_EQ(set.configurations[0].functions.size(), 1u) << "no function subset for the HID";
  EXPECT_EQ(dec::interfaces_with_compatible_id(set, "WINUSB"), std::vector<int>{0});
  EXPECT_EQ(dec::interfaces_with_property(set, "DeviceInterfaceGUIDs"), std::vector<int>{0});
  EXPECT_EQ(set.configurations[0].functions[0].features.size(), 2u) << "nothing else";

  const auto& features = set.configurations[0].functions[0].features;
  const auto compat = std::find_if(features.begin(), features.end(), is_winusb);
  ASSERT_NE(compat, features.end());
  EXPECT_EQ(compat->sub_compatible_id, "");
  const auto guid = std::find_if(features.begin(), features.end(), is_guid_property);
  ASSERT_NE(guid, features.end());
  EXPECT_EQ(guid->property_data_type, 7) << "REG_MULTI_SZ";
  EXPECT_TRUE(guid->multi_sz_terminated) << "the list ends NUL NUL";
  ASSERT_EQ(guid->property_strings.size(), 1u);
  EXPECT_EQ(dec::to_utf8(guid->property_strings[0]), kSpecGuid);
  EXPECT_EQ(std::string(palp::usb::kDeviceInterfaceGuid), kSpecGuid);
}

}  // namespace
