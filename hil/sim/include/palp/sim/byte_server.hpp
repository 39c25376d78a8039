// SPDX-License-Identifier: Apache-2.0
// A byte-stream server for palp-sim: one listening socket (TCP or a Unix-domain socket), one
// client at a time, non-blocking, driven by the simulator's own loop through poll().
//
// TCP listens on 127.0.0.1 unless told otherwise. A second client is accepted and closed at once
// with a one-line reason ("palp-sim: busy: another host is connected from ADDR since T"), so it
// learns the simulator is busy instead of hanging. Bytes to send wait in a bounded buffer; the
// simulator reads tx_pending() and stops advancing virtual time while the host does not drain
// (palp-sim stalls rather than drops). Received bytes wait in a bounded buffer too: when it is
// full the socket is not read (the peer's writes back up) until take_received() empties it.
// An idle rule (off unless set) frees the one slot from a client that holds it without talking:
// no complete unit (a frame or a line, ending with the delimiter) for idle_ms, or a partial
// unit left unfinished for partial_ms; such a client is told why in one line and closed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace palp::sim {

class ByteServer {
 public:
  /// Listens on host:port (port 0 picks a free one, see port()). Throws std::runtime_error with
  /// the address and the system's reason when it cannot.
  static ByteServer tcp(const std::string& host, std::uint16_t port);
  /// Listens on a Unix-domain socket at path. A stale socket file there (one no process
  /// listens on) is replaced; anything else (a live socket, a regular file, a directory) is
  /// refused with std::runtime_error naming the path, and left alone.
  static ByteServer unix_socket(const std::string& path);

  ByteServer(ByteServer&&) noexcept;
  ByteServer& operator=(ByteServer&&) noexcept;
  ByteServer(const ByteServer&) = delete;
  ByteServer& operator=(const ByteServer&) = delete;
  ~ByteServer();

  /// What one call to poll() saw.
  struct Events {
    bool connected = false;      ///< a client was accepted
    bool disconnected = false;   ///< the client went away (or was dropped)
    std::size_t received = 0;    ///< bytes appended to the receive buffer
  };
  /// Waits up to timeout_ms (0: do not wait) for activity, accepts, reads and writes what it can.
  Events poll(int timeout_ms);

  /// Bytes received and not yet taken. take_received() hands them over and empties the buffer.
  std::vector<std::uint8_t> take_received();
  /// Queues bytes for the client; false (nothing queued) when no client is connected or the
  /// buffer would exceed its bound (the caller stalls and retries).
  bool send(const std::uint8_t* data, std::size_t size);
  /// Bytes queued and not yet written to the socket.
  std::size_t tx_pending() const { return tx_.size() - tx_head_; }
  std::size_t tx_capacity() const { return tx_limit_; }
  void set_tx_capacity(std::size_t bytes) { tx_limit_ = bytes; }

  /// Receive-buffer bound (bytes); the socket is not read while the buffer holds this much.
  static constexpr std::size_t kRxLimit = 64 * 1024;

  /// When a silent or stuck client loses the slot (0: never).
  struct IdleRule {
    int idle_ms = 0;             ///< no complete unit for this long
    int partial_ms = 0;          ///< a started unit not finished for this long
    std::uint8_t delimiter = 0;  ///< what ends a unit (0 for COBS frames, '\n' for lines)
  };
  void set_idle_rule(const IdleRule& rule) { idle_ = rule; }
  const IdleRule& idle_rule() const { return idle_; }
  /// Clients closed by the idle rule.
  std::uint64_t idle_drops() const { return idle_drops_; }

  bool has_client() const { return client_ >= 0; }
  /// Drops the current client (fault injection: a dropped connection).
  void drop_client();
  /// The port a TCP server listens on (after port 0 was asked), 0 for a Unix socket.
  std::uint16_t port() const { return port_; }
  /// "tcp://127.0.0.1:40123" or "unix:///tmp/palp.sock".
  const std::string& address() const { return address_; }
  /// Clients refused because one was already connected.
  std::uint64_t refused_clients() const { return refused_; }

 private:
  ByteServer() = default;
  void close_all();
  void flush();
  void accept_client();
  void check_idle();
  void note_received(const std::uint8_t* data, std::size_t n);

  int listen_ = -1;
  int client_ = -1;
  std::uint16_t port_ = 0;
  std::string address_;
  std::string unix_path_;
  std::vector<std::uint8_t> rx_;
  std::vector<std::uint8_t> tx_;
  std::size_t tx_head_ = 0;
  std::size_t tx_limit_ = 256 * 1024;
  std::uint64_t refused_ = 0;
  IdleRule idle_{};
  std::uint64_t idle_drops_ = 0;
  std::string client_from_;              // "127.0.0.1:40123" or "pid 1234"
  std::string client_since_;             // UTC, ISO 8601
  std::int64_t last_unit_ms_ = 0;        // monotonic ms: connect or the last delimiter
  std::int64_t partial_since_ms_ = -1;   // first byte after the last delimiter; -1: none
};

}  // namespace palp::sim
