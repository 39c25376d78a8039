// SPDX-License-Identifier: Apache-2.0
// The robot client's link errors without a bridge: nothing listening, or a peer that accepts the
// connection and never answers. Both fail at once (no retry on the first connect) with a
// RobotLinkError that names the URI and the system's reason.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>

#include "palp/error.hpp"
#include "palp/robot.hpp"

namespace {

using testing::HasSubstr;

/// A loopback socket bound to an ephemeral port; listening or not.
struct LoopbackPort {
  explicit LoopbackPort(bool listen) {
    fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) return;
    socklen_t n = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
    port = ntohs(a.sin_port);
    if (listen) ::listen(fd, 1);
  }
  ~LoopbackPort() { ::close(fd); }
  std::string uri() const { return "modbus://127.0.0.1:" + std::to_string(port); }
  int fd = -1;
  std::uint16_t port = 0;
};

}  // namespace

TEST(RobotLink, NothingListeningFailsAtOnceNamingTheUriAndTheReason) {
  LoopbackPort bound_not_listening(false);
  ASSERT_NE(bound_not_listening.port, 0);
  try {
    palp::connect_robot(bound_not_listening.uri());
    FAIL() << "connected";
  } catch (const palp::RobotLinkError& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot connect to the robot bridge at " + bound_not_listening.uri() + ": Connection refused");
  }
}

TEST(RobotLink, APeerThatNeverAnswersFailsAfterTheResponseTimeout) {
  LoopbackPort silent(true);
  ASSERT_NE(silent.port, 0);
  palp::RobotOptions o;
  o.response_timeout = std::chrono::milliseconds(100);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    palp::connect_robot(silent.uri(), o);
    FAIL() << "connected";
  } catch (const palp::RobotLinkError& e) {
    EXPECT_EQ(std::string(e.what()), "the robot bridge at " + silent.uri() +
                                         " accepted the connection but did not answer the connect "
                                         "checks: Connection timed out");
  }
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_LT(took, std::chrono::milliseconds(1000));
}
