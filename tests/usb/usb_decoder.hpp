// SPDX-License-Identifier: Apache-2.0
// An independent decoder of USB descriptors, written from the tables of
// ../shared/reference/usb-dfu-facts.md (chapter 9 §1.4-§1.8, HID §2.1/§2.3, BOS §3, MS OS 2.0 §4),
// NOT from the firmware's builders: every offset, size and type code here is re-derived from the
// sheet, so a mistake in firmware/usb/src/descriptors.cpp is not repeated here. Host-only test
// code (throws DecodeError naming what is wrong and where).
//
// Each decode_* checks what the sheet fixes (bLength of fixed-size records, bDescriptorType,
// total lengths equal to the bytes present and to the sum of the parts, counts equal to the
// records found, nothing left over) and returns the fields for the tests to compare.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace palp::test::usbdec {

struct DecodeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Bytes = std::span<const std::uint8_t>;

// ---- chapter 9 -----------------------------------------------------------------------------------
struct Device {  // facts §1.4
  std::uint16_t bcd_usb = 0;
  std::uint8_t device_class = 0, device_subclass = 0, device_protocol = 0, max_packet0 = 0;
  std::uint16_t vendor = 0, product = 0, bcd_device = 0;
  std::uint8_t i_manufacturer = 0, i_product = 0, i_serial = 0, num_configurations = 0;
};
Device decode_device(Bytes b);

struct Endpoint {  // facts §1.7
  std::uint8_t address = 0;
  std::uint8_t transfer_type = 0;  ///< bmAttributes bits 1..0: 0 control 1 iso 2 bulk 3 interrupt
  std::uint16_t max_packet = 0;    ///< wMaxPacketSize bits 10..0
  std::uint8_t interval = 0;
};
struct HidClassDescriptor {  // facts §2.1
  std::uint16_t bcd_hid = 0;
  std::uint8_t country = 0;
  std::uint8_t report_type = 0;  ///< the (first) class descriptor's type
  std::uint16_t report_length = 0;
};
struct Interface {  // facts §1.6
  std::uint8_t number = 0, alternate = 0, interface_class = 0, subclass = 0, protocol = 0;
  std::uint8_t i_interface = 0;
  std::optional<HidClassDescriptor> hid;
  std::vector<Endpoint> endpoints;
};
struct Configuration {  // facts §1.5
  std::uint16_t total_length = 0;
  std::uint8_t num_interfaces = 0, value = 0, i_configuration = 0, attributes = 0, max_power = 0;
  std::vector<Interface> interfaces;
};
/// The whole block: walks every descriptor by its bLength, checks wTotalLength = bytes present,
/// bNumInterfaces = distinct interface numbers, bNumEndpoints = endpoints that follow, a HID
/// descriptor only right after a HID interface and before its endpoints.
Configuration decode_configuration(Bytes b);

/// String index 0 (facts §1.8): the LANGID list.
std::vector<std::uint16_t> decode_langids(Bytes b);
/// String n >= 1: UTF-16LE without terminator, returned as UTF-8 (BMP only; a surrogate or a
/// NUL is an error).
std::string decode_string(Bytes b);

// ---- HID report descriptor (facts §2.3) ----------------------------------------------------------
struct HidItem {
  std::uint8_t type = 0;  ///< 0 main, 1 global, 2 local
  std::uint8_t tag = 0;
  std::uint32_t data = 0;
  std::uint8_t size = 0;  ///< data bytes: 0, 1, 2 or 4
};
std::vector<HidItem> decode_hid_items(Bytes b);
/// What the items declare, by running the global/local state over the main items.
struct HidReports {
  std::uint32_t usage_page = 0;
  bool report_id_declared = false;
  std::uint32_t input_bits = 0, output_bits = 0, feature_bits = 0;
  std::int64_t logical_min = 0, logical_max = 0;  ///< of the last main item (signed, as HID says)
  int open_collections = 0;                       ///< after the last item (0 = balanced)
};
HidReports summarise_hid_report(Bytes b);

// ---- BOS and MS OS 2.0 (facts §3, §4) --------------------------------------------------------------
struct PlatformCapability {  // facts §3
  std::array<std::uint8_t, 16> uuid{};
  std::vector<std::uint8_t> data;
};
struct Bos {
  std::uint16_t total_length = 0;
  std::uint8_t num_capabilities = 0;
  std::vector<std::uint8_t> capability_types;  ///< bDevCapabilityType of each, in order
  std::vector<PlatformCapability> platform;
};
Bos decode_bos(Bytes b);

struct MsOs20Capability {  // facts §4.1, CapabilityData of the platform capability
  std::uint32_t windows_version = 0;
  std::uint16_t set_total_length = 0;
  std::uint8_t vendor_code = 0, alt_enum_code = 0;
};
/// The MS OS 2.0 UUID as the text the sheet gives, converted here to Microsoft's byte order.
std::array<std::uint8_t, 16> guid_bytes(const std::string& braced_guid);
MsOs20Capability decode_ms_os_20_capability(const PlatformCapability& cap);

struct MsFeature {  // facts §4.3: compatible ID (3) or registry property (4) or another type
  std::uint16_t type = 0;
  std::string compatible_id, sub_compatible_id;  ///< type 3, NULs stripped
  std::uint16_t property_data_type = 0;          ///< type 4
  std::u16string property_name;                  ///< type 4, without its NUL
  std::vector<std::u16string> property_strings;  ///< type 4 REG_MULTI_SZ: the list's entries
  bool multi_sz_terminated = false;              ///< REG_MULTI_SZ ends in NUL NUL
};
struct MsFunction {
  std::uint8_t first_interface = 0;
  std::vector<MsFeature> features;
};
struct MsConfiguration {
  std::uint8_t configuration = 0;
  std::vector<MsFeature> features;  ///< at configuration level, outside any function subset
  std::vector<MsFunction> functions;
};
struct MsOs20Set {
  std::uint32_t windows_version = 0;
  std::uint16_t total_length = 0;
  std::vector<MsFeature> device_features;  ///< before any configuration subset
  std::vector<MsConfiguration> configurations;
};
/// Walks the set: header first, wTotalLength = bytes present, each subset's length = its header
/// plus the records inside it, records of known types with their fixed wLength.
MsOs20Set decode_ms_os_20_set(Bytes b);

/// Where a feature applies: the bFirstInterface of each function subset holding it, in order;
/// -1 for one at device or configuration level (it would apply to the whole device).
std::vector<int> interfaces_with_compatible_id(const MsOs20Set& set, const std::string& id);
std::vector<int> interfaces_with_property(const MsOs20Set& set, const std::string& name);

std::string to_utf8(const std::u16string& s);

}  // namespace palp::test::usbdec
