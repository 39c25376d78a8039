// SPDX-License-Identifier: Apache-2.0
// serial:// baud rates and the termios speed constants they map to (serial_speeds.cpp holds the
// one table; palp::serial_bauds() in transport.hpp lists it).
#pragma once

#include <termios.h>

#include <cstdint>
#include <optional>
#include <string>

namespace palp::detail {

/// The termios speed for a baud rate; nullopt when termios has none.
std::optional<speed_t> termios_speed(std::uint32_t baud);

/// "baud 9601 is not a termios speed (supported: 50, 75, ..., 4000000)".
std::string unsupported_baud(std::uint32_t baud);

}  // namespace palp::detail
