// URIs: every accepted form parses to its parts; every malformed one is refused with a message
// that names the URI and the problem.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
  EXPECT_THAT(uri_error_of("tcp://x:1"), HasSubstr("unknown scheme 'tcp'"));
  EXPECT_THAT(uri_error_of("sim://localhost"), HasSubstr("sim:// needs host:port"));
  EXPECT_THAT(uri_error_of("sim://localhost:70000"),
              HasSubstr("port '70000' is not a number from 0 to 65535"));
  EXPECT_THAT(uri_error_of("sim://localhost:0"), HasSubstr("port 0 is not a port to connect to"));
  EXPECT_THAT(uri_error_of("usb://A?vid=zz"), HasSubstr("vid 'zz' is not a number"));
  EXPECT_THAT(uri_error_of("usb://A?speed=1"), HasSubstr("unknown parameter 'speed'"));
  EXPECT_THAT(uri_error_of("usb://A?vid"), HasSubstr("parameter 'vid' has no value"));
  EXPECT_THAT(uri_error_of("sim+inproc://"), HasSubstr("sim+inproc:// needs a phantom name (or none)"));
  EXPECT_THAT(uri_error_of("sim+inproc://none?seed"), HasSubstr("parameter 'seed' has no value"));
}
