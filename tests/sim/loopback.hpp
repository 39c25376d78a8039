// SPDX-License-Identifier: Apache-2.0
// A loopback client socket for the tests that talk to palp-sim's ports themselves.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>

namespace palp::sim::test {

/// A blocking TCP connection to 127.0.0.1:port; -1 when nothing listens. rcvbuf_bytes > 0 sets
/// a small receive buffer (set before connecting), so a host that does not read backs up soon.
inline int connect_loopback(std::uint16_t port, int rcvbuf_bytes = 0) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (rcvbuf_bytes > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf_bytes, sizeof rcvbuf_bytes);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace palp::sim::test
