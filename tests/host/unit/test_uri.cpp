// SPDX-License-Identifier: Apache-2.0
// URIs: every accepted form parses to its parts; every malformed one is refused with a message
// that names the URI and the problem.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "palp/error.hpp"
#include "palp/transport.hpp"

using palp::ConfigError;
using palp::parse_uri;
using palp::Uri;
using testing::HasSubstr;

TEST(Uri, SimTcpGivesHostAndPort) {
  const Uri u = parse_uri("sim://127.0.0.1:7070");
  EXPECT_EQ(u.scheme, Uri::Scheme::sim_tcp);
  EXPECT_EQ(u.host, "127.0.0.1");
  EXPECT_EQ(u.port, 7070);
}

TEST(Uri, TcpGivesHostAndPortLikeSim) {
  const Uri u = parse_uri("tcp://localhost:5555");
  EXPECT_EQ(u.scheme, Uri::Scheme::tcp);
  EXPECT_EQ(u.host, "localhost");
  EXPECT_EQ(u.port, 5555);
  EXPECT_EQ(u.text, "tcp://localhost:5555");
}

TEST(Uri, SerialGivesTheTtyPathAt115200BaudUnlessTold) {
  const Uri u = parse_uri("serial:///dev/ttyUSB0");
  EXPECT_EQ(u.scheme, Uri::Scheme::serial);
  EXPECT_EQ(u.path, "/dev/ttyUSB0");
  EXPECT_EQ(u.baud, 115200u);
  const Uri fast = parse_uri("serial:///dev/ttyACM1?baud=921600");
  EXPECT_EQ(fast.path, "/dev/ttyACM1");
  EXPECT_EQ(fast.baud, 921600u);
}

TEST(Uri, SerialBaudsAreTheTermiosSpeedsAscending) {
  const auto b = palp::serial_bauds();
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(b.front(), 50u);
  EXPECT_TRUE(std::is_sorted(b.begin(), b.end()));
  for (const std::uint32_t baud : {9600u, 19200u, 57600u, 115200u, 230400u})
    EXPECT_NE(std::find(b.begin(), b.end(), baud), b.end()) << baud;
  EXPECT_EQ(std::find(b.begin(), b.end(), 0u), b.end()) << "B0 hangs the line up";
}

TEST(Uri, SimWithAbsolutePathIsUnixSocket) {
  const Uri u = parse_uri("sim:///tmp/palp.sock");
  EXPECT_EQ(u.scheme, Uri::Scheme::sim_unix);
  EXPECT_EQ(u.path, "/tmp/palp.sock");
}

TEST(Uri, UsbSerialAndIdentityOverrides) {
  const Uri u = parse_uri("usb://PALP-0042?vid=0x1209&pid=16");
  EXPECT_EQ(u.scheme, Uri::Scheme::usb);
  EXPECT_EQ(u.serial, "PALP-0042");
  EXPECT_EQ(u.vid, 0x1209);
  EXPECT_EQ(u.pid, 16);
}

TEST(Uri, EmptySerialMeansTheOnlyDevice) {
  const Uri u = parse_uri("hid://");
  EXPECT_EQ(u.scheme, Uri::Scheme::hid);
  EXPECT_EQ(u.serial, "");
  EXPECT_FALSE(u.vid.has_value());
}

TEST(Uri, SimInprocGivesThePhantomAndItsParametersInOrder) {
  const Uri u = parse_uri("sim+inproc://solid_1d?seed=3&mount_mm=27,0,-25");
  EXPECT_EQ(u.scheme, Uri::Scheme::sim_inproc);
  EXPECT_EQ(u.phantom, "solid_1d");
  using P = std::pair<std::string, std::string>;
  EXPECT_EQ(u.parameters, (std::vector<P>{{"seed", "3"}, {"mount_mm", "27,0,-25"}}));
  EXPECT_TRUE(parse_uri("sim+inproc://none").parameters.empty());
}

TEST(Uri, SimInprocWhereTheSimulatorIsNotLinkedIsAConfigErrorNamingTheLibrary) {
  // sdk_unit_tests does not link palp_sim_inproc
  try {
    palp::open_transport("sim+inproc://none", std::chrono::milliseconds(100));
    FAIL() << "opened";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "transport URI 'sim+inproc://none': the in-process simulator is not linked into "
              "this program: link the palp_sim_inproc library (built with palp-sim), or start "
              "palp-sim and use sim://host:port");
  }
}

std::string uri_error_of(const std::string& uri) {
  try {
    parse_uri(uri);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Uri, MalformedUrisNameTheProblem) {
  EXPECT_THAT(uri_error_of("127.0.0.1:7070"), HasSubstr("'127.0.0.1:7070': no scheme"));
  EXPECT_THAT(uri_error_of("tcpip://x:1"), HasSubstr("unknown scheme 'tcpip'"));
  EXPECT_THAT(uri_error_of("sim://localhost"), HasSubstr("sim:// needs host:port"));
  EXPECT_THAT(uri_error_of("sim://localhost:70000"),
              HasSubstr("port '70000' is not a number from 0 to 65535"));
  EXPECT_THAT(uri_error_of("sim://localhost:0"), HasSubstr("port 0 is not a port to connect to"));
  EXPECT_THAT(uri_error_of("usb://A?vid=zz"), HasSubstr("vid 'zz' is not a number"));
  EXPECT_THAT(uri_error_of("usb://A?speed=1"), HasSubstr("unknown parameter 'speed'"));
  EXPECT_THAT(uri_error_of("usb://A?vid"), HasSubstr("parameter 'vid' has no value"));
  EXPECT_THAT(uri_error_of("sim+inproc://"),
              HasSubstr("sim+inproc:// needs a phantom name: sim+inproc://none for free air, or "
                        "one palp-sim --help lists"));
  EXPECT_THAT(uri_error_of("sim+inproc://none?seed"), HasSubstr("parameter 'seed' has no value"));
}

TEST(Uri, AnErrorListsEveryFormIncludingTcpAndSerial) {
  EXPECT_EQ(uri_error_of("udp://x:1"),
            "transport URI 'udp://x:1': unknown scheme 'udp' (expected tcp://host:port, "
            "serial:///dev/ttyX[?baud=N], usb://[serial], hid://[serial], sim://host:port, "
            "sim:///path/to/socket or sim+inproc://phantom[?key=value&...])");
}

/// The message without the list of accepted forms every parse error ends with.
std::string uri_problem_of(const std::string& uri) {
  const std::string e = uri_error_of(uri);
  return e.substr(0, e.find(" (expected tcp://"));
}

TEST(Uri, MalformedTcpAndSerialUrisNameTheProblem) {
  EXPECT_EQ(uri_problem_of("tcp://localhost"),
            "transport URI 'tcp://localhost': tcp:// needs host:port");
  EXPECT_EQ(uri_problem_of("tcp://:7070"), "transport URI 'tcp://:7070': tcp:// needs host:port");
  EXPECT_EQ(uri_problem_of("tcp:///tmp/sock"),
            "transport URI 'tcp:///tmp/sock': tcp:// needs host:port");
  EXPECT_EQ(uri_problem_of("tcp://h:0"),
            "transport URI 'tcp://h:0': port 0 is not a port to connect to");
  EXPECT_EQ(uri_problem_of("tcp://h:99999"),
            "transport URI 'tcp://h:99999': port '99999' is not a number from 0 to 65535");
  EXPECT_EQ(uri_problem_of("serial://ttyUSB0"),
            "transport URI 'serial://ttyUSB0': serial:// needs the tty's absolute path "
            "(serial:///dev/ttyUSB0)");
  EXPECT_EQ(uri_problem_of("serial://"),
            "transport URI 'serial://': serial:// needs the tty's absolute path "
            "(serial:///dev/ttyUSB0)");
  EXPECT_EQ(uri_problem_of("serial:///dev/ttyS0?parity=even"),
            "transport URI 'serial:///dev/ttyS0?parity=even': unknown parameter 'parity' "
            "(known: baud)");
  EXPECT_EQ(uri_problem_of("serial:///dev/ttyS0?baud"),
            "transport URI 'serial:///dev/ttyS0?baud': parameter 'baud' has no value");
  EXPECT_EQ(uri_problem_of("serial:///dev/ttyS0?baud=fast"),
            "transport URI 'serial:///dev/ttyS0?baud=fast': baud 'fast' is not a number");
  EXPECT_EQ(uri_problem_of("serial:///dev/ttyS0?baud=-9600"),
            "transport URI 'serial:///dev/ttyS0?baud=-9600': baud '-9600' is not a number");
}

TEST(Uri, ABaudThatIsNoTermiosSpeedIsRefusedListingTheSupportedOnes) {
  EXPECT_EQ(uri_problem_of("serial:///dev/ttyS0?baud=100000"),
            "transport URI 'serial:///dev/ttyS0?baud=100000': baud 100000 is not a termios speed "
            "(supported: 50, 75, 110, 134, 150, 200, 300, 600, 1200, 1800, 2400, 4800, 9600, "
            "19200, 38400, 57600, 115200, 230400, 460800, 500000, 576000, 921600, 1000000, "
            "1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000)");
  EXPECT_THAT(uri_error_of("serial:///dev/ttyS0?baud=0"),
              HasSubstr("baud 0 is not a termios speed"));
}

TEST(Uri, ABaudSetInAUriByHandIsCheckedWhenOpened) {
  Uri u = parse_uri("serial:///dev/ttyS0");
  u.baud = 12345;
  u.text = "serial:///dev/ttyS0?baud=12345";
  try {
    palp::open_transport(u, std::chrono::milliseconds(100));
    FAIL() << "opened";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("transport URI 'serial:///dev/ttyS0?baud=12345': baud 12345 "
                                    "is not a termios speed (supported: 50, "));
  }
}
