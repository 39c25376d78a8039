// SPDX-License-Identifier: Apache-2.0
// palp-sim's byte server over real loopback TCP and Unix sockets: bytes both ways, one client at
// a time, disconnects noticed, and a bounded send buffer that refuses instead of growing.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <cstring>
#include <string>
#include <vector>

#include "palp/sim/byte_server.hpp"

namespace palp::sim {
namespace {

int connect_tcp(std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0) << std::strerror(errno);
  return fd;
}

// Polls the server until pred() holds or 2 s of wall time pass.
template <class P>
bool pump(ByteServer& s, P pred) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < end) {
    s.poll(10);
    if (pred()) return true;
  }
  return false;
}

std::string read_some(int fd) {
  pollfd p{fd, POLLIN, 0};
  std::string out;
  while (::poll(&p, 1, 500) == 1) {
    char buf[256];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
    if (out.size() >= 5) break;
  }
  return out;
}

TEST(ByteServer, TcpListensOnLoopbackOnAnEphemeralPort) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  EXPECT_NE(s.port(), 0);
  EXPECT_EQ(s.address(), "tcp://127.0.0.1:" + std::to_string(s.port()));
}

TEST(ByteServer, CarriesBytesBothWaysOverTcp) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const int c = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  ASSERT_EQ(::write(c, "\x01\x02\x00\x03", 4), 4);
  std::vector<std::uint8_t> got;
  ASSERT_TRUE(pump(s, [&] {
    auto r = s.take_received();
    got.insert(got.end(), r.begin(), r.end());
    return got.size() >= 4;
  }));
  EXPECT_EQ(got, (std::vector<std::uint8_t>{1, 2, 0, 3}));
  const std::uint8_t reply[] = {'h', 'e', 'l', 'l', 'o'};
  ASSERT_TRUE(s.send(reply, sizeof reply));
  s.poll(0);
  EXPECT_EQ(read_some(c), "hello");
  ::close(c);
}

TEST(ByteServer, ASecondClientIsToldItIsBusyAndClosed) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const int first = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  const int second = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.refused_clients() == 1; }));
  EXPECT_EQ(read_some(second).rfind("palp-", 0), 0u);
  EXPECT_TRUE(s.has_client());
  ::close(second);
  ::close(first);
}

TEST(ByteServer, NoticesADisconnectAndAcceptsTheNextClient) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const int first = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  ::close(first);
  ASSERT_TRUE(pump(s, [&] { return !s.has_client(); }));
  const int second = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  ::close(second);
}

TEST(ByteServer, RefusesToQueueBeyondItsBoundWhileTheClientDoesNotRead) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  s.set_tx_capacity(64 * 1024);
  const int c = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  std::vector<std::uint8_t> chunk(16 * 1024, 0x55);
  int accepted = 0;
  for (int k = 0; k < 1000 && s.send(chunk.data(), chunk.size()); ++k) ++accepted;
  // the kernel buffers take some, then the server's own 64 KiB bound refuses the rest
  EXPECT_LT(accepted, 1000);
  EXPECT_LE(s.tx_pending(), s.tx_capacity());
  EXPECT_FALSE(s.send(chunk.data(), chunk.size()));
  ::close(c);
}

TEST(ByteServer, SendWithoutAClientQueuesNothing) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const std::uint8_t b = 1;
  EXPECT_FALSE(s.send(&b, 1));
  EXPECT_EQ(s.tx_pending(), 0u);
}

TEST(ByteServer, ServesAUnixSocketAndRemovesItsFileOnClose) {
  const std::string path = "/tmp/palp-sim-test-" + std::to_string(::getpid()) + ".sock";
  {
    ByteServer s = ByteServer::unix_socket(path);
    EXPECT_EQ(s.address(), "unix://" + path);
    const int c = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strcpy(a.sun_path, path.c_str());
    ASSERT_EQ(::connect(c, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
    ASSERT_EQ(::write(c, "x", 1), 1);
    ASSERT_TRUE(pump(s, [&] { return s.take_received().size() == 1; }));
    ::close(c);
  }
  EXPECT_NE(::access(path.c_str(), F_OK), 0);
}

TEST(ByteServer, RefusesAnAddressThatIsNotIpv4WithAClearMessage) {
  try {
    ByteServer::tcp("localhost:80", 0);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "palp-sim: 'localhost:80' is not an IPv4 address");
  }
}

// --- issue 17: who holds the slot, idle rules, the --unix path, the bounded receive buffer ----

TEST(ByteServer, ASecondClientIsToldWhoHoldsTheSlotAndSince) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const int first = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  sockaddr_in me{};
  socklen_t len = sizeof me;
  ::getsockname(first, reinterpret_cast<sockaddr*>(&me), &len);
  const int second = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.refused_clients() == 1; }));
  const std::string said = read_some(second);
  EXPECT_EQ(said.rfind("palp-sim: busy: another host is connected from 127.0.0.1:" +
                           std::to_string(ntohs(me.sin_port)) + " since 20", 0), 0u) << said;
  EXPECT_EQ(said.back(), '\n');
  EXPECT_EQ(std::count(said.begin(), said.end(), '\n'), 1);
  ::close(second);
  ::close(first);
}

TEST(ByteServer, ASilentClientLosesTheSlotAfterTheIdleTime) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  s.set_idle_rule({300, 0, 0});
  const int c = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 4; ++k) {  // whole units keep it: 4 x 100 ms, beyond the 300 ms
    const char frame[] = {'a', 'b', 0};
    ASSERT_EQ(::write(c, frame, 3), 3);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    while (std::chrono::steady_clock::now() < until) s.poll(5);
    s.take_received();
  }
  EXPECT_TRUE(s.has_client());
  ASSERT_TRUE(pump(s, [&] { return !s.has_client(); }));  // then silence
  // the last unit came at about 300 ms: not before 600 ms
  EXPECT_GT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(590));
  EXPECT_EQ(s.idle_drops(), 1u);
  EXPECT_NE(read_some(c).find("closing this connection: nothing complete received for 0.3 s"),
            std::string::npos);
  ::close(c);
}

TEST(ByteServer, AnUnfinishedUnitLosesTheSlotAfterThePartialTime) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  s.set_idle_rule({60000, 200, '\n'});
  const int c = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  ASSERT_EQ(::write(c, "status\nsta", 10), 10);  // a line, then half of one
  ASSERT_TRUE(pump(s, [&] { return !s.has_client(); }));
  EXPECT_EQ(s.idle_drops(), 1u);
  EXPECT_NE(read_some(c).find("an unfinished frame or line for 0.2 s"), std::string::npos);
  ::close(c);
}

TEST(ByteServer, AFullReceiveBufferIsNotReadUntilTaken) {
  ByteServer s = ByteServer::tcp("127.0.0.1", 0);
  const int c = connect_tcp(s.port());
  ASSERT_TRUE(pump(s, [&] { return s.has_client(); }));
  const std::vector<char> chunk(256 * 1024, 'x');
  ::fcntl(c, F_SETFL, O_NONBLOCK);
  [[maybe_unused]] const auto w = ::write(c, chunk.data(), chunk.size());
  for (int k = 0; k < 20; ++k) s.poll(5);
  EXPECT_EQ(s.take_received().size(), ByteServer::kRxLimit);  // no more than the bound
  ASSERT_TRUE(pump(s, [&] { return !s.take_received().empty(); }));  // the rest follows
  ::close(c);
}

std::string unix_test_path(const char* what) {
  return "/tmp/palp-sim-test-" + std::to_string(::getpid()) + "-" + what;
}

TEST(ByteServer, AUnixPathHoldingARegularFileIsRefusedAndKept) {
  const std::string path = unix_test_path("file");
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("precious\n", f);
    std::fclose(f);
  }
  try {
    ByteServer::unix_socket(path);
    ADD_FAILURE() << "a regular file was replaced";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + " exists and is not a socket"), std::string::npos)
        << e.what();
  }
  char buf[32] = {};
  std::FILE* f = std::fopen(path.c_str(), "r");
  ASSERT_NE(f, nullptr);
  EXPECT_NE(std::fgets(buf, sizeof buf, f), nullptr);
  std::fclose(f);
  EXPECT_STREQ(buf, "precious\n");
  ::unlink(path.c_str());
}

TEST(ByteServer, AUnixPathWithALiveListenerIsRefused) {
  const std::string path = unix_test_path("live");
  ByteServer first = ByteServer::unix_socket(path);
  try {
    ByteServer::unix_socket(path);
    ADD_FAILURE() << "a live socket was replaced";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + " is a socket another process listens on"),
              std::string::npos) << e.what();
  }
  EXPECT_EQ(::access(path.c_str(), F_OK), 0);  // still the first server's
}

TEST(ByteServer, AStaleUnixSocketIsReplaced) {
  const std::string path = unix_test_path("stale");
  {  // a socket file nobody listens on any more (a crashed server's)
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strcpy(a.sun_path, path.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    ::close(fd);
  }
  ASSERT_EQ(::access(path.c_str(), F_OK), 0);
  ByteServer s = ByteServer::unix_socket(path);
  EXPECT_EQ(s.address(), "unix://" + path);
}

}  // namespace
}  // namespace palp::sim
