// SPDX-License-Identifier: Apache-2.0
// The tests' side of sim::Server: a loopback client socket, a server on ephemeral ports, and
// stepping it in the test's thread.
#pragma once

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "palp/protocol/frame.hpp"
#include "palp/sim/server.hpp"
#include "loopback.hpp"

namespace palp::sim::test {

/// A blocking loopback client socket.
struct Client {
  /// rcvbuf_bytes > 0: a small receive buffer, so a host that does not read backs up soon
  explicit Client(std::uint16_t port, int rcvbuf_bytes = 0)
      : fd(connect_loopback(port, rcvbuf_bytes)) {}
  ~Client() {
    if (fd >= 0) ::close(fd);
  }
  void send_text(const std::string& s) const { ASSERT_EQ(::write(fd, s.data(), s.size()), static_cast<ssize_t>(s.size())); }
  template <class M>
  void send(const M& m, proto::u16 seq) const {
    std::vector<proto::u8> w(proto::kMaxWireFrame);
    w.resize(proto::encode_message(m, seq, 0, w.data(), w.size()));
    send_text(std::string(w.begin(), w.end()));
  }
  /// Opens the session (the device serves nothing else before it): Hello, seq 0.
  void hello() const {
    send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "test"}, 0);
  }
  /// What has arrived, without waiting.
  std::string take() const {
    std::string got;
    pollfd p{fd, POLLIN, 0};
    char buf[65536];
    while (::poll(&p, 1, 0) == 1) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n <= 0) break;
      got.append(buf, static_cast<std::size_t>(n));
    }
    return got;
  }
  int fd;
};

inline std::unique_ptr<Server> make_server(double pace, InstrumentOptions o = {}) {
  return std::make_unique<Server>(std::make_unique<Instrument>(std::move(o)),
                                  ByteServer::tcp("127.0.0.1", 0), ByteServer::tcp("127.0.0.1", 0),
                                  nullptr, pace);
}

inline std::uint16_t control_port(const Server& s) {
  const std::string b = s.banner();
  return static_cast<std::uint16_t>(std::stoul(b.substr(b.rfind(':') + 1)));
}

/// Steps until pred() or the wall time is up.
template <class Pred>
inline bool step_until(Server& s, Pred&& pred, std::chrono::milliseconds within = std::chrono::seconds(5)) {
  const auto end = std::chrono::steady_clock::now() + within;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > end) return false;
    s.step();
  }
  return true;
}

}  // namespace palp::sim::test
