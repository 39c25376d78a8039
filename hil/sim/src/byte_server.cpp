// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/byte_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
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

std::int64_t monotonic_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Who a client is: its TCP address and port, or a Unix socket peer's process id.
std::string peer_of(int fd) {
  sockaddr_storage a{};
  socklen_t len = sizeof a;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0 && a.ss_family == AF_INET) {
    const auto* in = reinterpret_cast<const sockaddr_in*>(&a);
    char ip[INET_ADDRSTRLEN] = "?";
    ::inet_ntop(AF_INET, &in->sin_addr, ip, sizeof ip);
    return std::string(ip) + ":" + std::to_string(ntohs(in->sin_port));
  }
  ucred cred{};
  socklen_t clen = sizeof cred;
  if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &clen) == 0)
    return "a local process (pid " + std::to_string(cred.pid) + ")";
  return "an unknown peer";
}

// A socket file at path that no process listens on (connect is refused) may be replaced;
// anything else is someone's and is refused. Returns normally when path is free to bind.
void clear_stale_socket(const std::string& path, const sockaddr_un& addr) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    fail("palp-sim: cannot inspect " + path);
  }
  if (!S_ISSOCK(st.st_mode))
    throw std::runtime_error("palp-sim: " + path +
                             " exists and is not a socket; not replacing it (remove it or "
                             "choose another --unix path)");
  const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (probe < 0) fail("socket");
  const int r = ::connect(probe, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
  const int why = errno;
  ::close(probe);
  if (r == 0 || why != ECONNREFUSED)
    throw std::runtime_error("palp-sim: " + path +
                             " is a socket another process listens on (or that cannot be "
                             "checked); not replacing it");
  if (::unlink(path.c_str()) != 0) fail("palp-sim: cannot remove the stale socket " + path);
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
  clear_stale_socket(path, addr);
  s.listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s.listen_ < 0) fail("socket");
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
    idle_ = o.idle_;
    idle_drops_ = o.idle_drops_;
    client_from_ = std::move(o.client_from_);
    client_since_ = std::move(o.client_since_);
    last_unit_ms_ = o.last_unit_ms_;
    partial_since_ms_ = o.partial_since_ms_;
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
  std::vector<std::uint8_t>().swap(tx_);  // release the memory, not only the size
  tx_head_ = 0;
  partial_since_ms_ = -1;
}

ByteServer::Events ByteServer::poll(int timeout_ms) {
  Events ev;
  pollfd fds[2] = {{listen_, POLLIN, 0}, {client_, 0, 0}};
  nfds_t n = 1;
  if (client_ >= 0) {
    // a full receive buffer is not read: the peer's writes back up in its socket
    const bool room = rx_.size() < kRxLimit;
    fds[1].events = static_cast<short>((room ? POLLIN : 0) | (tx_pending() > 0 ? POLLOUT : 0));
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
      while (rx_.size() < kRxLimit) {
        const std::size_t want = std::min(sizeof buf, kRxLimit - rx_.size());
        const ssize_t got = ::read(client_, buf, want);
        if (got > 0) {
          note_received(buf, static_cast<std::size_t>(got));
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
    const bool had = client_ >= 0;
    accept_client();
    ev.connected = !had && client_ >= 0;
  }
  if (client_ >= 0) {
    check_idle();
    if (client_ < 0) ev.disconnected = true;
  }
  if (client_ >= 0) flush();
  return ev;
}

void ByteServer::accept_client() {
  const int c = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
  if (c < 0) return;
  if (client_ >= 0) {
    const std::string busy = "palp-sim: busy: another host is connected from " + client_from_ +
                             " since " + client_since_ + "\n";
    [[maybe_unused]] const auto w = ::write(c, busy.data(), busy.size());
    ::close(c);
    ++refused_;
    return;
  }
  client_ = c;
  const int one = 1;
  ::setsockopt(c, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // fails harmlessly on Unix
  std::vector<std::uint8_t>().swap(rx_);
  client_from_ = peer_of(c);
  client_since_ = utc_now();
  last_unit_ms_ = monotonic_ms();
  partial_since_ms_ = -1;
}

void ByteServer::note_received(const std::uint8_t* data, std::size_t n) {
  const std::int64_t now = monotonic_ms();
  const void* last = std::memchr(data, idle_.delimiter, n);
  if (last != nullptr) {
    last_unit_ms_ = now;
    // bytes after the final delimiter start a new partial unit
    const std::uint8_t* end = data + n;
    const std::uint8_t* p = end;
    while (p > data && p[-1] != idle_.delimiter) --p;
    partial_since_ms_ = p < end ? now : -1;
  } else if (partial_since_ms_ < 0) {
    partial_since_ms_ = now;
  }
}

void ByteServer::check_idle() {
  const std::int64_t now = monotonic_ms();
  const char* why = nullptr;
  int limit_ms = 0;
  if (idle_.partial_ms > 0 && partial_since_ms_ >= 0 && now - partial_since_ms_ > idle_.partial_ms) {
    why = "an unfinished frame or line";
    limit_ms = idle_.partial_ms;
  } else if (idle_.idle_ms > 0 && now - last_unit_ms_ > idle_.idle_ms) {
    why = "nothing complete received";
    limit_ms = idle_.idle_ms;
  }
  if (why == nullptr) return;
  char line[160];
  const int len = std::snprintf(line, sizeof line,
                                "palp-sim: closing this connection: %s for %g s (the one client "
                                "slot is freed for another host)\n",
                                why, limit_ms / 1000.0);
  [[maybe_unused]] const auto w =
      ::send(client_, line, static_cast<std::size_t>(len), MSG_NOSIGNAL | MSG_DONTWAIT);
  ++idle_drops_;
  drop_client();
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
