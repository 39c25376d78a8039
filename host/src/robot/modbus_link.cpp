// SPDX-License-Identifier: Apache-2.0
// The libmodbus context behind ModbusLink.
#include "robot/modbus_link.hpp"

#include <modbus/modbus.h>

#include <cerrno>

#include "palp/error.hpp"

namespace palp::detail {

ModbusLink::ModbusLink(RobotUri uri, std::chrono::milliseconds response_timeout)
    : uri_(std::move(uri)), response_timeout_(response_timeout) {
  const std::string port = std::to_string(uri_.port);
  ctx_ = modbus_new_tcp_pi(uri_.host.c_str(), port.c_str());
  if (ctx_ == nullptr)
    throw ConfigError("robot URI '" + uri_.canonical + "': libmodbus cannot use it: " +
                      modbus_strerror(errno));
  const auto us = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(response_timeout_).count());
  modbus_set_response_timeout(ctx_, us / 1000000u, us % 1000000u);
  modbus_set_byte_timeout(ctx_, us / 1000000u, us % 1000000u);
  modbus_set_slave(ctx_, 1);  // robot-bridge.md §2: the host sends unit identifier 1
}

ModbusLink::~ModbusLink() {
  close();
  modbus_free(ctx_);
}

void ModbusLink::connect() {
  close();
  if (modbus_connect(ctx_) != 0) throw LinkDown{modbus_strerror(errno)};
  connected_ = true;
}

void ModbusLink::close() {
  if (connected_) modbus_close(ctx_);
  connected_ = false;
}

void ModbusLink::fail(const char* op, std::uint16_t address, std::uint16_t n) {
  const int e = errno;
  const std::string text = modbus_strerror(e);
  if (e >= EMBXILFUN && e <= EMBXGTAR)  // the bridge answered with a Modbus exception
    throw ProtocolError("robot bridge " + uri_.canonical + " refused " + op + " of " +
                        std::to_string(n) + " register(s) at " + std::to_string(address) +
                        " with a Modbus exception: " + text);
  close();  // a timeout or a garbled reply: a late reply would shift every later transaction
  throw LinkDown{text};
}

std::vector<std::uint16_t> ModbusLink::read(std::uint16_t address, std::uint16_t n) {
  if (!connected_) throw LinkDown{"not connected"};
  std::vector<std::uint16_t> regs(n);
  const int got = modbus_read_registers(ctx_, address, n, regs.data());
  if (got != n) {
    if (got >= 0) errno = EMBBADDATA;
    fail("a read (FC3)", address, n);
  }
  return regs;
}

void ModbusLink::write(std::uint16_t address, std::span<const std::uint16_t> regs) {
  if (!connected_) throw LinkDown{"not connected"};
  const int n = static_cast<int>(regs.size());
  const int done = modbus_write_registers(ctx_, address, n, regs.data());
  if (done != n) {
    if (done >= 0) errno = EMBBADDATA;
    fail("a write (FC16)", address, static_cast<std::uint16_t>(n));
  }
}

void ModbusLink::write_one(std::uint16_t address, std::uint16_t value) {
  if (!connected_) throw LinkDown{"not connected"};
  if (modbus_write_register(ctx_, address, value) != 1) fail("a write (FC6)", address, 1);
}

}  // namespace palp::detail
