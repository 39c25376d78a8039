// The USB device core (firmware/usb/README.md). Being written: so far the SETUP packet decoder.
#pragma once

#include <cstdint>

#include "palp/usb/hardware.hpp"

namespace palp::usb {

/// The 8 bytes of a SETUP packet as received (little-endian words), decoded.
SetupPacket parse_setup(const std::uint8_t* bytes);

}  // namespace palp::usb
