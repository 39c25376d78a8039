// SPDX-License-Identifier: Apache-2.0
// ModbusServer: palp-sim's Modbus TCP server for the robot bridge (protocol/robot-bridge.md §2),
// built on libmodbus, single-threaded and non-blocking: palp-sim's main loop calls poll().
//
//   - Listens on one address (loopback by default) and port (0: an ephemeral one).
//   - ONE client: a second connection is accepted, told "palp-sim: busy: another host is
//     connected from ADDR since T" in one text line (no Modbus frame: a client reports a bad
//     reply or the close; a person with nc reads why) and closed.
//   - Requests are cut out of the byte stream here (MBAP header: protocol 0, length 2..254);
//     a partial request waits for its remaining bytes, so it never blocks the simulator, but
//     at most kPartialMs; a client with no whole request for kIdleMs is closed too (the SDK's
//     robot client writes its heartbeat every watchdog / 4, at most 2.5 s). At most 4 KiB of
//     unparsed bytes and 64 unsent replies are kept: beyond, the socket is not read.
//     A malformed header closes the connection.
//   - FC3, FC6 and FC16 go to the handler, which validates them (§3) and answers with the
//     exception to send; other function codes get exception 01, and a PDU whose length or
//     byte count does not fit its function code gets 03. Only then does libmodbus build the
//     reply (modbus_reply / modbus_reply_exception) from a scratch mapping, so libmodbus's own
//     mapping never decides what is writable.
//   - A reply delay (fault knob) holds every reply for that much wall time; the request itself
//     is applied at once (a late reply after a host's timeout, as on a real link).
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "palp/sim/robot_bridge.hpp"

typedef struct _modbus modbus_t;
typedef struct _modbus_mapping_t modbus_mapping_t;

namespace palp::sim {

/// What the server serves (RobotWorld in palp-sim).
class ModbusHandler {
 public:
  virtual ~ModbusHandler() = default;
  /// FC3: fill out[0..count) or answer an exception.
  virtual ModbusException read(std::uint16_t address, std::uint16_t count, std::uint16_t* out) = 0;
  /// FC6 (single) or FC16.
  virtual ModbusException write(std::uint16_t address, std::span<const std::uint16_t> regs,
                                bool single) = 0;
  /// The client's connection closed (by the client, a malformed request, or a drop).
  virtual void closed() = 0;
};

class ModbusServer {
 public:
  /// Listens now. Throws std::runtime_error saying what failed.
  ModbusServer(const std::string& address, std::uint16_t port);
  ~ModbusServer();
  ModbusServer(const ModbusServer&) = delete;
  ModbusServer& operator=(const ModbusServer&) = delete;

  std::uint16_t port() const { return port_; }
  /// "tcp://<address>:<port>"
  std::string address() const;

  /// Accepts, reads and serves whatever is ready, and sends the replies that are due; never
  /// waits. wall_us: the wall clock (any epoch), for the reply delay.
  void poll(ModbusHandler& handler, std::uint64_t wall_us);
  bool has_client() const { return client_ >= 0; }
  /// Closes the client's connection now (the robot-drop knob).
  void drop_client(ModbusHandler& handler);
  /// No whole request for this long (wall time) closes the client, and a partial request left
  /// unfinished for kPartialMs.
  static constexpr std::uint64_t kIdleMs = 30'000;
  static constexpr std::uint64_t kPartialMs = 2'000;
  /// Tests shorten them.
  void set_timeouts_ms(std::uint64_t idle_ms, std::uint64_t partial_ms) {
    idle_us_ = idle_ms * 1000;
    partial_us_ = partial_ms * 1000;
  }
  void set_reply_delay_ms(double ms) { reply_delay_us_ = ms > 0 ? static_cast<std::uint64_t>(ms * 1e3) : 0; }
  double reply_delay_ms() const { return static_cast<double>(reply_delay_us_) / 1e3; }

  struct Counters {
    std::uint64_t connections = 0, refused = 0, requests = 0, exceptions = 0, malformed = 0;
    std::uint64_t timeouts = 0;  ///< clients closed idle or with a partial request
  };
  const Counters& counters() const { return counters_; }

 private:
  struct Reply {
    std::uint64_t due_us;
    std::vector<std::uint8_t> request;
    ModbusException exception;
    std::uint16_t address;
    std::vector<std::uint16_t> values;  // FC3: the registers read when the request came
  };
  void accept_clients(ModbusHandler& handler, std::uint64_t wall_us);
  bool receive(ModbusHandler& handler, std::uint64_t wall_us);
  void serve(ModbusHandler& handler, std::vector<std::uint8_t> request, std::uint64_t wall_us);
  bool send_due(std::uint64_t wall_us);
  void close_client(ModbusHandler& handler);

  std::string listen_address_;
  std::uint16_t port_ = 0;
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* mapping_ = nullptr;
  int listen_ = -1;
  int client_ = -1;
  std::vector<std::uint8_t> rx_;
  std::deque<Reply> replies_;
  std::uint64_t reply_delay_us_ = 0;
  std::uint64_t idle_us_ = kIdleMs * 1000, partial_us_ = kPartialMs * 1000;
  std::uint64_t last_request_us_ = 0;   // the client's connect or last whole request
  std::uint64_t partial_since_us_ = 0;  // when the unparsed bytes began (0: none)
  std::string client_from_, client_since_;
  Counters counters_;
};

}  // namespace palp::sim
