// STAND-IN (usbcore): contract 2's declarations only (/work/team19.md), so the device core
// compiles until helper usbdesc's real header and its descriptors.cpp are merged. usbdesc owns
// this file; the lead takes usbdesc's version at the merge. The device core uses only the names
// declared here (the values follow usbdesc's branch: vendor code 0x50, wIndex 7).
#pragma once

#include <cstdint>
#include <span>

namespace palp::usb {

/// GET_DESCRIPTOR(type, index) for language langid: the descriptor's bytes; empty = none (STALL).
/// Covers device, configuration (whole block), string (0 = LANGID list), BOS, and HID report
/// (type 0x22) / HID (0x21) descriptors. For the HID types langid is the request's wIndex (the
/// interface number).
std::span<const std::uint8_t> find_descriptor(std::uint8_t type, std::uint8_t index,
                                              std::uint16_t langid);

/// The vendor request code that fetches the MS OS 2.0 descriptor set (bmRequestType 0xC0,
/// wIndex 7) and the set itself.
inline constexpr std::uint8_t kMsOs20VendorCode = 0x50;
/// wIndex of that request that asks for the descriptor set (MS OS 2.0: MS_OS_20_DESCRIPTOR_INDEX).
inline constexpr std::uint16_t kMsOs20DescriptorIndex = 7;
std::span<const std::uint8_t> ms_os_20_descriptor_set();

/// Sets the serial-number string (ASCII, <= 24 chars) served as string index 3; called at boot.
bool set_serial_number(const char* ascii);

}  // namespace palp::usb
