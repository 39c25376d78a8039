// SPDX-License-Identifier: Apache-2.0
// The HID interface's report descriptor (protocol/SPEC.md §3.1): one vendor-defined 64-byte input
// report and one 64-byte output report, no report ID, so every report is 64 stream bytes.
// Items from ../shared/reference/usb-dfu-facts.md §2.3 (prefix byte = tag << 4 | type << 2 |
// size code). Each report states its own globals, although globals persist, so either half reads
// on its own.
#pragma once

#include <array>
#include <cstdint>

#include "palp/protocol/usb.hpp"

namespace palp::usb {

inline constexpr std::array<std::uint8_t, 34> kHidReport{
    0x06, 0x00, 0xFF,  // Usage Page (vendor-defined 0xFF00)
    0x09, 0x01,        // Usage (0x01)
    0xA1, 0x01,        // Collection (Application)
    // input report: device -> host
    0x09, 0x02,        //   Usage (0x02)
    0x15, 0x00,        //   Logical Minimum (0)
    0x26, 0xFF, 0x00,  //   Logical Maximum (255): the 2-byte form; 1-byte 0xFF would be -1
    0x75, 0x08,        //   Report Size (8 bits)
    0x95, 0x40,        //   Report Count (64)
    0x81, 0x02,        //   Input (Data, Variable, Absolute)
    // output report: host -> device
    0x09, 0x03,        //   Usage (0x03)
    0x15, 0x00,        //   Logical Minimum (0)
    0x26, 0xFF, 0x00,  //   Logical Maximum (255)
    0x75, 0x08,        //   Report Size (8 bits)
    0x95, 0x40,        //   Report Count (64)
    0x91, 0x02,        //   Output (Data, Variable, Absolute)
    0xC0,              // End Collection
};
static_assert(palp::proto::usb::kHidReportSize == 0x40, "Report Count above is the report size");

}  // namespace palp::usb
