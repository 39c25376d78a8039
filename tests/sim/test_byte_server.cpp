// palp-sim's byte server over real loopback TCP and Unix sockets: bytes both ways, one client at
// a time, disconnects noticed, and a bounded send buffer that refuses instead of growing.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
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

}  // namespace
}  // namespace palp::sim
