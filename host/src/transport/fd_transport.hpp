// SPDX-License-Identifier: Apache-2.0
// The transport over one file descriptor carrying the framed byte stream: a connected socket
// (tcp://, sim://) or a raw tty (serial://). poll() bounds every wait by the caller's timeout;
// a closed peer (EOF, a hung-up tty, a reset connection) is a ConnectionError.
#pragma once

#include <cstdint>
#include <string>

#include "palp/transport.hpp"

namespace palp::detail {

/// What an FdTransport is connected to, for its behaviour and its messages.
struct FdPeer {
  std::string uri;     ///< the URI as given (uri())
  std::string name;    ///< starts every message: "palp-sim at sim://127.0.0.1:7070"
  bool socket = true;  ///< send(MSG_NOSIGNAL) (no SIGPIPE) rather than write()
  std::uint32_t max_bytes_per_s = 0;
};

class FdTransport final : public Transport {
 public:
  /// Takes fd (non-blocking) and closes it when destroyed.
  FdTransport(int fd, FdPeer peer);
  ~FdTransport() override;
  FdTransport(const FdTransport&) = delete;
  FdTransport& operator=(const FdTransport&) = delete;

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override;
  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override;
  std::uint32_t max_device_bytes_per_s() const override { return peer_.max_bytes_per_s; }
  const std::string& uri() const override { return peer_.uri; }

 private:
  [[noreturn]] void closed() const;
  int fd_;
  FdPeer peer_;
};

}  // namespace palp::detail
