// SPDX-License-Identifier: Apache-2.0
// Parsing "modbus://host[:port]".
#include "robot/robot_uri.hpp"

#include <charconv>
#include <string_view>

#include "palp/error.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"

namespace palp::detail {
namespace {

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw ConfigError("robot URI '" + text + "': " + why + " (expected modbus://host[:port], port " +
                    std::to_string(proto::rb::kDefaultPort) + " by default)");
}

std::uint16_t parse_port(const std::string& text, std::string_view v) {
  unsigned value = 0;
  const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
  if (v.empty() || ec != std::errc{} || p != v.data() + v.size() || value < 1 || value > 65535)
    bad(text, "port '" + std::string(v) + "' is not a number from 1 to 65535");
  return static_cast<std::uint16_t>(value);
}

}  // namespace

RobotUri parse_robot_uri(const std::string& text) {
  const std::size_t sep = text.find("://");
  if (sep == std::string::npos) bad(text, "no scheme");
  const std::string scheme = text.substr(0, sep);
  if (scheme != "modbus") bad(text, "unknown scheme '" + scheme + "'");
  std::string_view rest = std::string_view(text).substr(sep + 3);
  for (const char c : rest)
    if (c == '/' || c == '?' || c == '#' || c == '@' || c == ' ')
      bad(text, std::string("unexpected '") + c + "' (a robot URI has no path, query or user)");
  RobotUri u;
  u.port = proto::rb::kDefaultPort;
  std::string_view port;
  bool has_port = false;
  bool v6 = false;
  if (!rest.empty() && rest[0] == '[') {
    const std::size_t close = rest.find(']');
    if (close == std::string_view::npos) bad(text, "'[' without ']' around an IPv6 address");
    u.host = std::string(rest.substr(1, close - 1));
    const std::string_view after = rest.substr(close + 1);
    if (!after.empty()) {
      if (after[0] != ':') bad(text, "expected ':port' after ']'");
      port = after.substr(1);
      has_port = true;
    }
    v6 = true;
  } else {
    const std::size_t colon = rest.find(':');
    if (colon != std::string_view::npos && rest.find(':', colon + 1) != std::string_view::npos)
      bad(text, "an IPv6 address must be written in brackets, [::1]");
    u.host = std::string(rest.substr(0, colon));
    if (colon != std::string_view::npos) {
      port = rest.substr(colon + 1);
      has_port = true;
    }
  }
  if (u.host.empty()) bad(text, "no host");
  if (has_port) u.port = parse_port(text, port);
  u.canonical = "modbus://" + (v6 ? "[" + u.host + "]" : u.host) + ":" + std::to_string(u.port);
  return u;
}

}  // namespace palp::detail
