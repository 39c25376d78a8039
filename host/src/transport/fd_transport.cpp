// SPDX-License-Identifier: Apache-2.0
#include "transport/fd_transport.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "palp/error.hpp"

namespace palp::detail {
namespace {
constexpr short kHungUp = POLLHUP | POLLERR | POLLNVAL;
}  // namespace

FdTransport::FdTransport(int fd, FdPeer peer) : fd_(fd), peer_(std::move(peer)) {}
FdTransport::~FdTransport() { ::close(fd_); }

void FdTransport::closed() const {
  throw ConnectionError(peer_.name + " closed the connection" +
                        (peer_.socket ? "" : " (hung up: unplugged, or its other end closed)"));
}

void FdTransport::write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) {
  std::size_t off = 0;
  while (off < bytes.size()) {
    pollfd p{fd_, POLLOUT, 0};
    const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (r < 0 && errno == EINTR) continue;
    if (r == 0)
      throw TimeoutError(peer_.name + " to take " + std::to_string(bytes.size() - off) + " bytes",
                         static_cast<double>(timeout.count()) / 1000.0, std::nullopt);
    const ssize_t n = peer_.socket
                          ? ::send(fd_, bytes.data() + off, bytes.size() - off, MSG_NOSIGNAL)
                          : ::write(fd_, bytes.data() + off, bytes.size() - off);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN && !(p.revents & kHungUp)) continue;
      if (errno == EAGAIN || errno == EIO || errno == EPIPE) closed();
      throw ConnectionError(peer_.name + ": send failed: " + std::strerror(errno));
    }
    off += static_cast<std::size_t>(n);
  }
}

std::size_t FdTransport::read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) {
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (r <= 0) return 0;  // nothing in time, or a signal: the caller reads again
  const ssize_t n =
      peer_.socket ? ::recv(fd_, buf.data(), buf.size(), 0) : ::read(fd_, buf.data(), buf.size());
  if (n == 0) closed();
  if (n < 0) {
    if (errno == EINTR) return 0;
    if (errno == EAGAIN && !(p.revents & kHungUp)) return 0;
    // a tty whose other end is gone reads EIO (a pty's master closed, a USB adapter unplugged)
    if (errno == EAGAIN || errno == EIO) closed();
    throw ConnectionError(peer_.name + ": receive failed: " + std::strerror(errno));
  }
  return static_cast<std::size_t>(n);
}

}  // namespace palp::detail
