// SPDX-License-Identifier: Apache-2.0
// The USB descriptors of the probe controller (protocol/SPEC.md §3.1; contract 2 of the USB
// device: the core's GET_DESCRIPTOR and vendor requests call these). The identity and the
// endpoint layout come from palp/protocol/usb.hpp (one definition, shared with the SDK).
//
//   device         bcdUSB 0x0201 (Windows reads the BOS only from 2.01 on), class 0/0/0 (each
//                  interface names its class; two single-interface functions need no IAD),
//                  bMaxPacketSize0 64, idVendor/idProduct from usb.hpp, bcdDevice = the firmware
//                  version the core reports (DeviceIdentity), one configuration
//   configuration  64 bytes: bus-powered, 100 mA; interface 0 vendor (0xFF) with bulk OUT 0x01
//                  and IN 0x81; interface 1 HID (its HID descriptor) with interrupt OUT 0x02 and
//                  IN 0x82 every 1 ms; all endpoints 64 bytes
//   strings        0 LANGID 0x0409; 1 manufacturer, 2 product, 3 serial (set_serial_number),
//                  4 and 5 the interfaces' names
//   HID report     vendor page 0xFF00: one 64-byte input and one 64-byte output report, no
//                  report ID (34 bytes)
//   BOS            the MS OS 2.0 platform capability only (33 bytes)
//   MS OS 2.0 set  for a composite device, 178 bytes: set header, configuration subset, one
//                  function subset for interface 0 only (CompatibleID "WINUSB" and the registry
//                  property DeviceInterfaceGUIDs = kDeviceInterfaceGuid); the HID interface has
//                  none, so Windows binds its in-box HID driver. Fetched by the vendor request
//                  bmRequestType 0xC0, bRequest kMsOs20VendorCode, wIndex kMsOs20DescriptorIndex.
//
// Everything but the serial string is built at compile time, with its lengths checked there.
// Freestanding C++20: no heap, no exceptions; the same source builds for the MCU and the tests.
#pragma once

#include <cstdint>
#include <span>

namespace palp::usb {

/// GET_DESCRIPTOR(type, index) for language langid: the descriptor's bytes; empty = none (STALL).
/// Covers device (0x01), configuration (0x02, the whole block), string (0x03; index 0 = the
/// LANGID list), BOS (0x0F), and the HID (0x21) and HID report (0x22) descriptors.
/// langid is the request's wIndex: for strings n >= 1 it must be 0x0409 or 0 (a host asking
/// before it read the LANGID list); for the HID types it is the interface number and must be
/// the HID interface's. Device qualifier (0x06) and other-speed (0x07): empty (full speed only).
/// The caller returns at most wLength bytes of the span (and a ZLP if the rule asks for one).
std::span<const std::uint8_t> find_descriptor(std::uint8_t type, std::uint8_t index,
                                              std::uint16_t langid);

/// The vendor request code that fetches the MS OS 2.0 descriptor set (bmRequestType 0xC0,
/// wIndex kMsOs20DescriptorIndex) and the set itself. 0x50 is 'P' (palp); any byte would do.
inline constexpr std::uint8_t kMsOs20VendorCode = 0x50;
/// wIndex of that request that asks for the descriptor set (MS OS 2.0: MS_OS_20_DESCRIPTOR_INDEX).
inline constexpr std::uint16_t kMsOs20DescriptorIndex = 7;
std::span<const std::uint8_t> ms_os_20_descriptor_set();

/// The vendor interface's DeviceInterfaceGUID, as Windows registers it (generated once for palp,
/// 2026-11-26; never change it: host software on Windows finds the device by it).
inline constexpr char kDeviceInterfaceGuid[] = "{69F08DC9-9AF8-419C-B6F5-404171392868}";

/// String descriptor indices (device and interface descriptors name these).
inline constexpr std::uint8_t kStringManufacturer = 1;
inline constexpr std::uint8_t kStringProduct = 2;
inline constexpr std::uint8_t kStringSerialNumber = 3;
inline constexpr std::uint8_t kStringVendorInterface = 4;
inline constexpr std::uint8_t kStringHidInterface = 5;

/// The longest serial number served (the STM32's 96-bit UID as 24 hex digits).
inline constexpr std::size_t kMaxSerialChars = 24;

/// Sets the serial-number string (ASCII, <= 24 chars) served as string index 3; called at boot,
/// before the device connects. Returns false, and serves what it kept, when ascii was null or
/// empty (served: "0"), longer than kMaxSerialChars (served: its first 24 characters) or held a
/// character outside printable ASCII 0x20..0x7E (served as '?'). Until it is called the serial
/// is "0".
bool set_serial_number(const char* ascii);

}  // namespace palp::usb
