// SPDX-License-Identifier: Apache-2.0
// The control requests the device core answers, and the rules it applies that need no hardware
// (usb-dfu-facts.md §1.1-§1.2, §1.11, §2.2, §4.4; the section is cited at each constant). Pure
// functions, tested on their own and used by Device<H> (device.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/usb/hardware.hpp"

namespace palp::usb {

/// bmRequestType (facts §1.1): D7 direction, D6..5 type, D4..0 recipient.
namespace request_type {
inline constexpr std::uint8_t kDirectionIn = 0x80;
inline constexpr std::uint8_t kTypeMask = 0x60;
inline constexpr std::uint8_t kStandard = 0x00;
inline constexpr std::uint8_t kClass = 0x20;
inline constexpr std::uint8_t kVendor = 0x40;
inline constexpr std::uint8_t kRecipientMask = 0x1F;
inline constexpr std::uint8_t kDevice = 0x00;
inline constexpr std::uint8_t kInterface = 0x01;
inline constexpr std::uint8_t kEndpoint = 0x02;
}  // namespace request_type

/// Standard requests (facts §1.2).
namespace standard {
inline constexpr std::uint8_t kGetStatus = 0x00;
inline constexpr std::uint8_t kClearFeature = 0x01;
inline constexpr std::uint8_t kSetFeature = 0x03;
inline constexpr std::uint8_t kSetAddress = 0x05;
inline constexpr std::uint8_t kGetDescriptor = 0x06;
inline constexpr std::uint8_t kGetConfiguration = 0x08;
inline constexpr std::uint8_t kSetConfiguration = 0x09;
inline constexpr std::uint8_t kGetInterface = 0x0A;
inline constexpr std::uint8_t kSetInterface = 0x0B;
/// Feature selectors (facts §1.2).
inline constexpr std::uint16_t kEndpointHalt = 0;
inline constexpr std::uint16_t kDeviceRemoteWakeup = 1;
}  // namespace standard

/// Descriptor types the core looks at (facts §1.3, §2.1).
namespace descriptor_type {
inline constexpr std::uint8_t kConfiguration = 0x02;
inline constexpr std::uint8_t kHid = 0x21;
inline constexpr std::uint8_t kHidReport = 0x22;
}  // namespace descriptor_type

/// HID class requests (facts §2.2; wIndex = the HID interface).
namespace hid {
inline constexpr std::uint8_t kGetReport = 0x01;
inline constexpr std::uint8_t kGetIdle = 0x02;
inline constexpr std::uint8_t kSetReport = 0x09;
inline constexpr std::uint8_t kSetIdle = 0x0A;
inline constexpr std::uint8_t kReportTypeInput = 1;
inline constexpr std::uint8_t kReportTypeOutput = 2;
}  // namespace hid

/// Endpoint 0's packet size (the device descriptor's bMaxPacketSize0).
inline constexpr std::size_t kControlPacketSize = 64;

/// The 8 bytes of a SETUP packet as received (little-endian words), decoded (facts §1.1).
SetupPacket parse_setup(const std::uint8_t* bytes);

/// The control IN data stage's ZLP rule (facts §1.11): with `reply` bytes sent for a request
/// that allowed `w_length`, the stage ends with a zero-length packet when the reply is shorter
/// than wLength and a non-zero exact multiple of the packet size (a short last packet, or
/// reaching wLength, ends it otherwise).
constexpr bool control_in_needs_zlp(std::size_t reply, std::size_t w_length,
                                    std::size_t packet = kControlPacketSize) {
  return reply < w_length && reply > 0 && reply % packet == 0;
}

/// How many of the `pending` stream bytes starting at `bytes` one HID report may carry
/// (usb.hpp, SPEC §3.1 "HID reports"): all 64 when 64 or more are pending; otherwise the bytes
/// up to and including the last frame delimiter 0x00 among them (the report is zero-padded
/// after it), or 0 when there is none (a frame's start: wait for its end, never pad inside it).
std::size_t hid_report_take(const std::uint8_t* bytes, std::size_t pending);

}  // namespace palp::usb
