#include "palp/sim/byte_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace palp::sim {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error(what + ": " + std::strerror(errno));
}

void set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) fail("fcntl(O_NONBLOCK)");
}

}  // namespace

ByteServer ByteServer::tcp(const std::string& host, std::uint16_t port) {
  ByteServer s;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1)
    throw std::runtime_error("palp-sim: '" + host + "' is not an IPv4 address");
  s.listen_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s.listen_ < 0) fail("socket");
  const int one = 1;
  ::setsockopt(s.listen_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(s.listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0)
    fail("palp-sim: cannot listen on " + host + ":" + std::to_string(port));
  if (::listen(s.listen_, 4) < 0) fail("listen");
  set_nonblocking(s.listen_);
  socklen_t len = sizeof addr;
  ::getsockname(s.listen_, reinterpret_cast<sockaddr*>(&addr), &len);
  s.port_ = ntohs(addr.sin_port);
  s.address_ = "tcp://" + host + ":" + std::to_string(s.port_);
  return s;
}

ByteServer ByteServer::unix_socket(const std::string& path) {
  ByteServer s;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof addr.sun_path)
    throw std::runtime_error("palp-sim: Unix socket path '" + path + "' is empty or longer than " +
                             std::to_string(sizeof addr.sun_path - 1) + " bytes");
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  s.listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s.listen_ < 0) fail("socket");
  ::unlink(path.c_str());
  if (::bind(s.listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0)
    fail("palp-sim: cannot listen on " + path);
  if (::listen(s.listen_, 4) < 0) fail("listen");
  set_nonblocking(s.listen_);
  s.unix_path_ = path;
  s.address_ = "unix://" + path;
  return s;
}

ByteServer::ByteServer(ByteServer&& o) noexcept { *this = std::move(o); }

ByteServer& ByteServer::operator=(ByteServer&& o) noexcept {
  if (this != &o) {
    close_all();
    listen_ = std::exchange(o.listen_, -1);
    client_ = std::exchange(o.client_, -1);
    port_ = o.port_;
    address_ = std::move(o.address_);
    unix_path_ = std::exchange(o.unix_path_, {});
    rx_ = std::move(o.rx_);
    tx_ = std::move(o.tx_);
    tx_head_ = std::exchange(o.tx_head_, 0);
    tx_limit_ = o.tx_limit_;
    refused_ = o.refused_;
  }
  return *this;
}

ByteServer::~ByteServer() { close_all(); }

void ByteServer::close_all() {
  drop_client();
  if (listen_ >= 0) ::close(listen_);
  listen_ = -1;
  if (!unix_path_.empty()) ::unlink(unix_path_.c_str());
  unix_path_.clear();
}

void ByteServer::drop_client() {
  if (client_ >= 0) ::close(client_);
  client_ = -1;
  tx_.clear();
  tx_head_ = 0;
}

ByteServer::Events ByteServer::poll(int timeout_ms) {
  Events ev;
  pollfd fds[2] = {{listen_, POLLIN, 0}, {client_, 0, 0}};
  nfds_t n = 1;
  if (client_ >= 0) {
    fds[1].events = static_cast<short>(POLLIN | (tx_pending() > 0 ? POLLOUT : 0));
    n = 2;
  }
  const int r = ::poll(fds, n, timeout_ms);
  if (r < 0) {
    if (errno == EINTR) return ev;
    fail("poll");
  }
  // the client's bytes and its hang-up first: a host that closes and reconnects at once must
  // find the old connection gone, not be refused as a second client
  if (n == 2 && client_ >= 0 && fds[1].revents != 0) {
    if (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) {
      std::uint8_t buf[4096];
      while (true) {
        const ssize_t got = ::read(client_, buf, sizeof buf);
        if (got > 0) {
          rx_.insert(rx_.end(), buf, buf + got);
          ev.received += static_cast<std::size_t>(got);
          continue;
        }
        if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
        if (got < 0 && errno == EINTR) continue;
        drop_client();  // 0: orderly close; < 0: reset
        ev.disconnected = true;
        break;
      }
    }
  }
  if (fds[0].revents & POLLIN) {
    const int c = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (c >= 0) {
      if (client_ >= 0) {
        static const char busy[] = "palp-sim: another client is connected; one at a time\n";
        [[maybe_unused]] const auto w = ::write(c, busy, sizeof busy - 1);
        ::close(c);
        ++refused_;
      } else {
        client_ = c;
        const int one = 1;
        ::setsockopt(c, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // fails harmlessly on Unix
        rx_.clear();
        ev.connected = true;
      }
    }
  }
  if (client_ >= 0) flush();
  return ev;
}

void ByteServer::flush() {
  while (tx_pending() > 0) {
    const ssize_t w =
        ::send(client_, tx_.data() + tx_head_, tx_pending(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (w > 0) {
      tx_head_ += static_cast<std::size_t>(w);
      continue;
    }
    if (w < 0 && errno == EINTR) continue;
    if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    drop_client();
    return;
  }
  if (tx_head_ > 0 && tx_head_ == tx_.size()) {
    tx_.clear();
    tx_head_ = 0;
  } else if (tx_head_ > 64 * 1024) {
    tx_.erase(tx_.begin(), tx_.begin() + static_cast<std::ptrdiff_t>(tx_head_));
    tx_head_ = 0;
  }
}

std::vector<std::uint8_t> ByteServer::take_received() { return std::exchange(rx_, {}); }

bool ByteServer::send(const std::uint8_t* data, std::size_t size) {
  if (client_ < 0 || tx_pending() + size > tx_limit_) return false;
  tx_.insert(tx_.end(), data, data + size);
  flush();
  return true;
}

}  // namespace palp::sim
