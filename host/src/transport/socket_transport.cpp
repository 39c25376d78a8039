// SPDX-License-Identifier: Apache-2.0
// tcp://host:port, sim://host:port and sim:///path: the framed byte stream over a TCP or
// Unix-domain socket (palp-sim, or the firmware under QEMU with its UART on a TCP server).
#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "palp/error.hpp"
#include "transport/factories.hpp"
#include "transport/fd_transport.hpp"

namespace palp::detail {
namespace {

int connect_with_timeout(int fd, const sockaddr* addr, socklen_t len,
                         std::chrono::milliseconds timeout) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  int r = ::connect(fd, addr, len);
  if (r != 0 && errno == EINPROGRESS) {
    pollfd p{fd, POLLOUT, 0};
    r = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (r == 0) {
      errno = ETIMEDOUT;
      return -1;
    }
    int err = 0;
    socklen_t el = sizeof err;
    ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &el);
    if (err != 0) {
      errno = err;
      return -1;
    }
    r = 0;
  }
  return r;
}

}  // namespace

std::unique_ptr<Transport> open_socket_transport(const Uri& uri,
                                                 std::chrono::milliseconds timeout) {
  const bool tcp = uri.scheme == Uri::Scheme::tcp;
  const auto fail = [&](const std::string& why) -> std::unique_ptr<Transport> {
    if (tcp)
      throw ConnectionError("cannot reach " + uri.text + ": " + why +
                            " (is palp-sim, or QEMU with -serial tcp:HOST:PORT,server=on, "
                            "listening there?)");
    throw ConnectionError("cannot reach palp-sim at " + uri.text + ": " + why +
                          " (is palp-sim running? start it with `palp-sim` and use the address "
                          "its first line prints)");
  };
  // palp-sim stalls rather than drops, so a socket has no fixed ceiling; the figure is what the
  // simulator can produce at 40 kHz with every channel, many times over
  const auto connected = [&](int fd) -> std::unique_ptr<Transport> {
    return std::make_unique<FdTransport>(
        fd, FdPeer{uri.text, (tcp ? "the controller at " : "palp-sim at ") + uri.text, true,
                   100'000'000u});
  };
  if (uri.scheme == Uri::Scheme::sim_unix) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    if (uri.path.size() >= sizeof addr.sun_path) return fail("socket path too long");
    std::memcpy(addr.sun_path, uri.path.c_str(), uri.path.size() + 1);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (connect_with_timeout(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr, timeout) != 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      return fail(why);
    }
    return connected(fd);
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  const std::string port = std::to_string(uri.port);
  if (const int e = ::getaddrinfo(uri.host.c_str(), port.c_str(), &hints, &res); e != 0)
    return fail(std::string("cannot resolve host: ") + ::gai_strerror(e));
  std::string why = "no address";
  for (addrinfo* a = res; a != nullptr; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    if (connect_with_timeout(fd, a->ai_addr, a->ai_addrlen, timeout) == 0) {
      ::freeaddrinfo(res);
      int one = 1;
      ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      return connected(fd);
    }
    why = std::strerror(errno);
    ::close(fd);
  }
  ::freeaddrinfo(res);
  return fail(why);
}

}  // namespace palp::detail
