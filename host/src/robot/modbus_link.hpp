// SPDX-License-Identifier: Apache-2.0
// One libmodbus TCP context to a robot bridge, used by one thread only (libmodbus contexts are not
// thread-safe): connect/close, and whole blocks of the register map read (FC3) and written
// (FC16, or FC6 for one host-control register). No floats; registers <-> blocks through
// proto::rb::encode/decode.
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "palp/protocol/robot_bridge/codec.hpp"
#include "robot/robot_uri.hpp"

typedef struct _modbus modbus_t;

namespace palp::detail {

/// A broken link (no connection, a response timeout, a reply that does not match its request):
/// the owner closes, reconnects and retries. what: the errno text.
struct LinkDown {
  std::string what;
};

class ModbusLink {
 public:
  ModbusLink(RobotUri uri, std::chrono::milliseconds response_timeout);
  ~ModbusLink();
  ModbusLink(const ModbusLink&) = delete;
  ModbusLink& operator=(const ModbusLink&) = delete;

  const RobotUri& uri() const { return uri_; }
  /// Opens the TCP connection (closing any open one first). Throws LinkDown.
  void connect();
  void close();
  bool connected() const { return connected_; }

  /// FC3 of n registers from address. Throws LinkDown, or ProtocolError for a Modbus exception.
  std::vector<std::uint16_t> read(std::uint16_t address, std::uint16_t n);
  /// FC16 of the registers from address.
  void write(std::uint16_t address, std::span<const std::uint16_t> regs);
  /// FC6 of one register.
  void write_one(std::uint16_t address, std::uint16_t value);

  /// FC16 of a whole block, in one request.
  template <class B>
  void write_block(const B& b) {
    std::array<std::uint16_t, B::kLength> regs{};
    proto::rb::encode(b, std::span<std::uint16_t, B::kLength>(regs));
    write(B::kAddress, regs);
  }

 private:
  [[noreturn]] void fail(const char* op, std::uint16_t address, std::uint16_t n);

  RobotUri uri_;
  std::chrono::milliseconds response_timeout_;
  modbus_t* ctx_ = nullptr;
  bool connected_ = false;
};

}  // namespace palp::detail
