// The controller's USB identity and endpoint layout (SPEC.md §3.1): shared by the firmware's
// USB descriptors and the SDK's usb:// and hid:// transports, so both sides use one definition.
//
// Vendor ID 0x1209 is the pid.codes open-hardware vendor ID; product ID 0x0001 is its test
// product ID, used until palp has a product ID of its own. Both can be overridden on the host
// (the `vid` and `pid` URI parameters, or PALP_USB_VID / PALP_USB_PID) so a board flashed with
// another identity is still reachable.
#pragma once

#include <cstdint>

namespace palp::proto::usb {

inline constexpr std::uint16_t kVendorId = 0x1209;   ///< pid.codes (open-hardware VID)
inline constexpr std::uint16_t kProductId = 0x0001;  ///< pid.codes test PID, until one is allocated

/// Interface 0: vendor-specific (class 0xFF), the byte stream over two bulk endpoints.
inline constexpr std::uint8_t kVendorInterface = 0;
inline constexpr std::uint8_t kVendorInterfaceClass = 0xFF;
inline constexpr std::uint8_t kBulkOutEndpoint = 0x01;  ///< host -> device
inline constexpr std::uint8_t kBulkInEndpoint = 0x81;   ///< device -> host
inline constexpr std::uint16_t kBulkPacketSize = 64;    ///< full speed

/// Interface 1: HID, 64-byte reports without report IDs, interrupt endpoints every 1 ms.
inline constexpr std::uint8_t kHidInterface = 1;
inline constexpr std::uint8_t kHidOutEndpoint = 0x02;
inline constexpr std::uint8_t kHidInEndpoint = 0x82;
inline constexpr std::uint16_t kHidReportSize = 64;
inline constexpr std::uint8_t kHidIntervalMs = 1;

/// What each transport carries at most, device to host (SPEC.md §9): full-speed bulk, 19 packets
/// of 64 bytes per 1 ms frame; HID, one 64-byte report per 1 ms interval.
inline constexpr std::uint32_t kBulkBytesPerS = 19u * 64u * 1000u;
inline constexpr std::uint32_t kHidBytesPerS = 64u * 1000u;

}  // namespace palp::proto::usb
