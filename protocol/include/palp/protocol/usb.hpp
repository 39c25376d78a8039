// SPDX-License-Identifier: Apache-2.0
// The controller's USB identity and endpoint layout (SPEC.md §3.1): shared by the firmware's
// USB descriptors and the SDK's usb:// and hid:// transports, so both sides use one definition.
//
// Vendor ID 0x1209 is the pid.codes open-hardware vendor ID; product ID 0x0001 is its test
// product ID, used until palp has a product ID of its own. Both can be overridden on the host
// (the `vid` and `pid` URI parameters, or PALP_USB_VID / PALP_USB_PID) so a board flashed with
// another identity is still reachable.
//
// The device is full speed, one configuration, two interfaces:
//
//   interface 0  vendor-specific (class 0xFF, subclass 0, protocol 0)
//                EP 0x01 bulk OUT 64   host -> device byte stream
//                EP 0x81 bulk IN  64   device -> host byte stream
//   interface 1  HID, no report IDs, 64-byte input and output reports
//                EP 0x02 interrupt OUT 64, 1 ms     host -> device byte stream
//                EP 0x82 interrupt IN  64, 1 ms     device -> host byte stream
//
// Device descriptor: idVendor kVendorId, idProduct kProductId, bcdDevice = bcd_device(firmware
// major, minor), iSerialNumber MUST name a string unique per board (the SDK picks a controller
// by it: usb://SERIAL, hid://SERIAL), iProduct names the product.
//
// Zero-length packets on the bulk endpoints, both directions: a sender whose write (a run of
// stream bytes handed to the USB stack at once) is a non-zero multiple of kBulkPacketSize bytes
// long follows it with a zero-length packet, so the receiver's transfer, armed for more than
// one packet, completes at once instead of waiting for more bytes. A receiver treats a
// zero-length packet as no bytes. The frame boundaries themselves are in the stream (the 0x00
// delimiter), never in the packets.
#pragma once

#include <cstdint>

namespace palp::proto::usb {

inline constexpr std::uint16_t kVendorId = 0x1209;   ///< pid.codes (open-hardware VID)
inline constexpr std::uint16_t kProductId = 0x0001;  ///< pid.codes test PID, until one is allocated

/// The STM32's ROM DFU bootloader (ST's vendor ID and its DFU product ID; AN2606 family,
/// ../shared/reference/usb-dfu-facts.md §5.1): the identity a board shows after the bootloader
/// request, for flashing. host/udev/70-palp.rules gives both identities to the logged-in user.
inline constexpr std::uint16_t kStBootloaderVendorId = 0x0483;
inline constexpr std::uint16_t kStBootloaderProductId = 0xDF11;

/// Interface 0: vendor-specific (class 0xFF), the byte stream over two bulk endpoints.
inline constexpr std::uint8_t kVendorInterface = 0;
inline constexpr std::uint8_t kVendorInterfaceClass = 0xFF;
inline constexpr std::uint8_t kBulkOutEndpoint = 0x01;  ///< host -> device
inline constexpr std::uint8_t kBulkInEndpoint = 0x81;   ///< device -> host
inline constexpr std::uint16_t kBulkPacketSize = 64;    ///< full speed wMaxPacketSize

/// Interface 1: HID, 64-byte reports without report IDs, interrupt endpoints every 1 ms.
/// Every report carries 64 stream bytes; a report not filled by pending bytes is zero-padded,
/// and only after a frame's 0x00 delimiter (SPEC.md §3).
inline constexpr std::uint8_t kHidInterface = 1;
inline constexpr std::uint8_t kHidOutEndpoint = 0x02;
inline constexpr std::uint8_t kHidInEndpoint = 0x82;
inline constexpr std::uint16_t kHidReportSize = 64;
inline constexpr std::uint8_t kHidIntervalMs = 1;
/// hidapi writes begin with the report ID; with no report IDs declared it is this byte, which
/// the host's HID stack does not send (it is not part of the stream).
inline constexpr std::uint8_t kHidReportId = 0x00;

/// What each transport carries at most, device to host (SPEC.md §9): full-speed bulk, 19 packets
/// of 64 bytes per 1 ms frame; HID, one 64-byte report per 1 ms interval.
inline constexpr std::uint32_t kBulkBytesPerS = 19u * 64u * 1000u;
inline constexpr std::uint32_t kHidBytesPerS = 64u * 1000u;

/// bcdDevice carries the firmware's major.minor version as 0xMMmm, each of major and minor as
/// two BCD digits (0..99): firmware 1.2 is 0x0102, 0.13 is 0x0013, 12.34 is 0x1234.
constexpr std::uint16_t bcd_device(std::uint8_t major, std::uint8_t minor) {
  const auto bcd = [](unsigned v) { return ((v / 10) << 4) | (v % 10); };
  return static_cast<std::uint16_t>((bcd(major % 100u) << 8) | bcd(minor % 100u));
}
/// True when every nibble of bcd is a decimal digit (a bcdDevice written by bcd_device()).
constexpr bool bcd_device_valid(std::uint16_t bcd) {
  for (int shift = 0; shift < 16; shift += 4)
    if (((bcd >> shift) & 0xF) > 9) return false;
  return true;
}
/// The firmware major and minor version a valid bcdDevice carries.
constexpr std::uint8_t bcd_device_major(std::uint16_t bcd) {
  return static_cast<std::uint8_t>(((bcd >> 12) & 0xF) * 10 + ((bcd >> 8) & 0xF));
}
constexpr std::uint8_t bcd_device_minor(std::uint16_t bcd) {
  return static_cast<std::uint8_t>(((bcd >> 4) & 0xF) * 10 + (bcd & 0xF));
}
static_assert(bcd_device(1, 2) == 0x0102 && bcd_device(12, 34) == 0x1234);
static_assert(bcd_device_major(0x1234) == 12 && bcd_device_minor(0x1234) == 34);
static_assert(!bcd_device_valid(0x010A));

}  // namespace palp::proto::usb
