// SPDX-License-Identifier: Apache-2.0
// Robot URIs: "modbus://host[:port]" gives host and port (30005 by default); everything else is
// refused with a ConfigError that quotes the URI and says what is wrong.
#include <gtest/gtest.h>

#include "palp/error.hpp"
#include "palp/robot.hpp"
#include "robot/robot_uri.hpp"

using palp::detail::parse_robot_uri;
using palp::detail::RobotUri;

namespace {

std::string error_of(const std::string& uri) {
  try {
    parse_robot_uri(uri);
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

const std::string kExpected = " (expected modbus://host[:port], port 30005 by default)";

}  // namespace

TEST(RobotUri, HostWithoutPortGetsTheDefaultPort30005) {
  const RobotUri u = parse_robot_uri("modbus://172.31.1.147");
  EXPECT_EQ(u.host, "172.31.1.147");
  EXPECT_EQ(u.port, 30005);
  EXPECT_EQ(u.canonical, "modbus://172.31.1.147:30005");
}

TEST(RobotUri, HostAndPort) {
  const RobotUri u = parse_robot_uri("modbus://kuka-cell.local:30007");
  EXPECT_EQ(u.host, "kuka-cell.local");
  EXPECT_EQ(u.port, 30007);
  EXPECT_EQ(u.canonical, "modbus://kuka-cell.local:30007");
}

TEST(RobotUri, BracketedIpv6WithAndWithoutPort) {
  EXPECT_EQ(parse_robot_uri("modbus://[::1]:1502").host, "::1");
  EXPECT_EQ(parse_robot_uri("modbus://[::1]:1502").port, 1502);
  EXPECT_EQ(parse_robot_uri("modbus://[fe80::1]").canonical, "modbus://[fe80::1]:30005");
}

TEST(RobotUri, MalformedUrisAreRefusedWithExactMessages) {
  EXPECT_EQ(error_of("172.31.1.147:30005"), "robot URI '172.31.1.147:30005': no scheme" + kExpected);
  EXPECT_EQ(error_of("tcp://172.31.1.147"), "robot URI 'tcp://172.31.1.147': unknown scheme 'tcp'" + kExpected);
  EXPECT_EQ(error_of("modbus://"), "robot URI 'modbus://': no host" + kExpected);
  EXPECT_EQ(error_of("modbus://:30005"), "robot URI 'modbus://:30005': no host" + kExpected);
  EXPECT_EQ(error_of("modbus://host:"), "robot URI 'modbus://host:': port '' is not a number from 1 to 65535" + kExpected);
  EXPECT_EQ(error_of("modbus://host:0"), "robot URI 'modbus://host:0': port '0' is not a number from 1 to 65535" + kExpected);
  EXPECT_EQ(error_of("modbus://host:65536"), "robot URI 'modbus://host:65536': port '65536' is not a number from 1 to 65535" + kExpected);
  EXPECT_EQ(error_of("modbus://host:30x"), "robot URI 'modbus://host:30x': port '30x' is not a number from 1 to 65535" + kExpected);
  EXPECT_EQ(error_of("modbus://host:-1"), "robot URI 'modbus://host:-1': port '-1' is not a number from 1 to 65535" + kExpected);
  EXPECT_EQ(error_of("modbus://host/robot"), "robot URI 'modbus://host/robot': unexpected '/' (a robot URI has no path, query or user)" + kExpected);
  EXPECT_EQ(error_of("modbus://host?unit=2"), "robot URI 'modbus://host?unit=2': unexpected '?' (a robot URI has no path, query or user)" + kExpected);
  EXPECT_EQ(error_of("modbus://::1:502"), "robot URI 'modbus://::1:502': an IPv6 address must be written in brackets, [::1]" + kExpected);
  EXPECT_EQ(error_of("modbus://[::1"), "robot URI 'modbus://[::1': '[' without ']' around an IPv6 address" + kExpected);
  EXPECT_EQ(error_of("modbus://[::1]x"), "robot URI 'modbus://[::1]x': expected ':port' after ']'" + kExpected);
}

TEST(RobotUri, ConnectRobotRefusesABadUriBeforeConnecting) {
  try {
    palp::connect_robot("modbus://127.0.0.1:0");
    FAIL() << "connected";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "robot URI 'modbus://127.0.0.1:0': port '0' is not a number from 1 to 65535" + kExpected);
  }
}

TEST(RobotUri, ConnectRobotRefusesAWatchdogOutsideTheMapsRange) {
  palp::RobotOptions o;
  o.watchdog = std::chrono::milliseconds(50);
  try {
    palp::connect_robot("modbus://127.0.0.1:1", o);
    FAIL() << "connected";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "robot watchdog 50 ms is outside 100..10000 ms (robot-bridge.md §5.3)");
  }
}
