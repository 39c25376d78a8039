// SPDX-License-Identifier: Apache-2.0
// The live view's server (host/cli/live_server.hpp) in-process: an event client that stops
// reading is dropped once its unsent events pass the limit, while a client that reads gets every
// event; and which addresses count as loopback. (Requests, answers and binds through palpctl:
// tests/cli/live_view/test_live_server.js.)
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "live_server.hpp"

namespace palpctl {
namespace {

int subscribe(std::uint16_t port, int receive_buffer_bytes) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer_bytes, sizeof receive_buffer_bytes);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  const std::string request = "GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
  EXPECT_EQ(::write(fd, request.data(), request.size()), static_cast<ssize_t>(request.size()));
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return fd;
}

// Reads what is there; returns how many complete "event: big" messages it held so far.
std::size_t read_events(int fd, std::string& seen) {
  char buf[1 << 16];
  ssize_t n;
  while ((n = ::read(fd, buf, sizeof buf)) > 0) seen.append(buf, static_cast<std::size_t>(n));
  std::size_t count = 0;
  for (std::size_t at = 0; (at = seen.find("event: big\n", at)) != std::string::npos; ++at) ++count;
  return count;
}

TEST(LiveServer, DropsAnEventClientThatStopsReadingAndKeepsStreamingToOneThatReads) {
  LiveServer server({}, "<!doctype html><title>t</title>");
  const int slow = subscribe(server.port(), 4096);
  const int reader = subscribe(server.port(), 1 << 20);
  for (int k = 0; k < 100 && server.event_clients() < 2; ++k)
    server.serve(std::chrono::milliseconds(10));
  ASSERT_EQ(server.event_clients(), 2u);

  const std::string payload(64 * 1024, 'x');
  std::string seen;
  int sent = 0;
  // 32 MiB in all: eight times the limit, far more than the kernel's buffers hold
  for (; sent < 512 && server.slow_clients_dropped() == 0; ++sent) {
    server.broadcast("big", payload);
    server.serve(std::chrono::milliseconds(1));
    read_events(reader, seen);
  }
  EXPECT_EQ(server.slow_clients_dropped(), 1u) << "after " << sent << " events of 64 KiB";
  RecordProperty("events_of_64KiB_before_the_drop", sent);
  EXPECT_EQ(server.event_clients(), 1u);
  for (int k = 0; k < 10; ++k) {
    server.broadcast("big", payload);
    ++sent;
  }
  std::size_t got = 0;
  for (int k = 0; k < 500 && got < static_cast<std::size_t>(sent); ++k) {
    server.serve(std::chrono::milliseconds(2));
    got = read_events(reader, seen);
  }
  EXPECT_EQ(got, static_cast<std::size_t>(sent)) << "the reading client missed events";
  ::close(slow);
  ::close(reader);
}

TEST(LiveServer, LoopbackIsAllOf127Slash8AndNothingElse) {
  EXPECT_TRUE(is_loopback_ipv4("127.0.0.1"));
  EXPECT_TRUE(is_loopback_ipv4("127.255.1.2"));
  EXPECT_FALSE(is_loopback_ipv4("0.0.0.0"));
  EXPECT_FALSE(is_loopback_ipv4("10.0.0.1"));
  EXPECT_FALSE(is_loopback_ipv4("128.0.0.1"));
  EXPECT_FALSE(is_loopback_ipv4("localhost"));  // a name, not an address
  EXPECT_FALSE(is_loopback_ipv4("127.0.0.1 "));
}

}  // namespace
}  // namespace palpctl
