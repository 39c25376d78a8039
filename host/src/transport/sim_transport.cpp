// sim://host:port and sim:///path: palp-sim's byte stream over a TCP or Unix-domain socket.
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

namespace palp::detail {
namespace {

class SimTransport final : public Transport {
 public:
  SimTransport(int fd, std::string uri) : fd_(fd), uri_(std::move(uri)) {}
  ~SimTransport() override { ::close(fd_); }

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
    std::size_t off = 0;
    while (off < bytes.size()) {
      pollfd p{fd_, POLLOUT, 0};
      const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
      if (r < 0 && errno == EINTR) continue;
      if (r == 0)
        throw TimeoutError("palp-sim at " + uri_ + " to take " +
                               std::to_string(bytes.size() - off) + " bytes",
                           static_cast<double>(timeout.count()) / 1000.0, std::nullopt);
      const ssize_t n = ::send(fd_, bytes.data() + off, bytes.size() - off, MSG_NOSIGNAL);
      if (n < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        throw ConnectionError("palp-sim at " + uri_ + ": send failed: " + std::strerror(errno));
      }
      off += static_cast<std::size_t>(n);
    }
  }

  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override {
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (r < 0 && errno == EINTR) return 0;
    if (r <= 0) return 0;
    const ssize_t n = ::recv(fd_, buf.data(), buf.size(), 0);
    if (n == 0) throw ConnectionError("palp-sim at " + uri_ + " closed the connection");
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) return 0;
      throw ConnectionError("palp-sim at " + uri_ + ": receive failed: " + std::strerror(errno));
    }
    return static_cast<std::size_t>(n);
  }

  // A socket has no fixed ceiling; palp-sim stalls rather than drops. The figure is what the
  // simulator can produce at 40 kHz with every channel, many times over.
  std::uint32_t max_device_bytes_per_s() const override { return 100'000'000u; }
  const std::string& uri() const override { return uri_; }

 private:
  int fd_;
  std::string uri_;
};

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

std::unique_ptr<Transport> open_sim_transport(const Uri& uri, std::chrono::milliseconds timeout) {
  const auto fail = [&](const std::string& why) -> std::unique_ptr<Transport> {
    throw ConnectionError("cannot reach palp-sim at " + uri.text + ": " + why +
                          " (is palp-sim running? start it with `palp-sim` and use the address "
                          "its first line prints)");
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
    return std::make_unique<SimTransport>(fd, uri.text);
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
      return std::make_unique<SimTransport>(fd, uri.text);
    }
    why = std::strerror(errno);
    ::close(fd);
  }
  ::freeaddrinfo(res);
  return fail(why);
}

}  // namespace palp::detail
