// SPDX-License-Identifier: Apache-2.0
// The robot bridge's URI: "modbus://host[:port]" (robot.hpp, connect_robot).
#pragma once

#include <cstdint>
#include <string>

namespace palp::detail {

struct RobotUri {
  std::string host;        ///< a name, an IPv4 address, or an IPv6 address without brackets
  std::uint16_t port = 0;  ///< proto::rb::kDefaultPort when the URI names none
  std::string canonical;   ///< "modbus://host:port" (IPv6 in brackets)
};

/// Parses a robot URI. Throws ConfigError quoting the URI and saying what is wrong.
RobotUri parse_robot_uri(const std::string& text);

}  // namespace palp::detail
