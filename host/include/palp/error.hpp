// SPDX-License-Identifier: Apache-2.0
// The SDK's errors: one small hierarchy, every message written for the person who reads it.
//
//   palp::Error                  base of everything the SDK throws
//   ├── ConfigError              a bad argument, URI, option or setting; nothing was sent
//   ├── ConnectionError          the device could not be reached, or the link was lost
//   ├── TimeoutError             a reply or an event did not come in time; names what was
//   │                            waited for and carries the latest health counters
//   ├── VersionError             the handshake verdict is "incompatible" (names both versions
//   │                            and what to do)
//   ├── DeviceError              the device refused a request (its Nak, with the error code)
//   ├── FaultError               the device's fault latch tripped while the SDK waited on it
//   ├── ProtocolError            the device sent bytes the SDK cannot accept
//   ├── RecordingError           a recording file is malformed (names the file, line, problem)
//   ├── DataError                the data cannot give the result asked of it: too few samples,
//   │                            no contact, a NaN sample, nothing to fit (the analysis throws
//   │                            it; an experiment turns it into its analysis_reason, while a
//   │                            bad setting stays a ConfigError and propagates)
//   ├── RobotRejectedError       the robot bridge refused a command (its result code; for a bad
//   │                            parameter the register's address and name)
//   ├── RobotFaultError          the robot faulted or was safety-stopped during a motion
//   ├── FlashError               a firmware update failed after the device left its
//   │                            application (names the device's state and how to recover)
//   └── RobotLinkError           (a ConnectionError) the robot bridge is unreachable or its
//                                heartbeat stopped
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "palp/health.hpp"

namespace palp {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ConfigError : public Error {
 public:
  using Error::Error;
};

class ConnectionError : public Error {
 public:
  using Error::Error;
};

class TimeoutError : public Error {
 public:
  /// what: the thing waited for ("DeviceInfo reply to Hello", "program to finish").
  TimeoutError(const std::string& what, double timeout_s, std::optional<HealthCounters> health);
  const std::string& waited_for() const { return waited_for_; }
  double timeout_s() const { return timeout_s_; }
  /// The newest health counters the SDK had when the wait ended (none before the first read).
  const std::optional<HealthCounters>& health() const { return health_; }

 private:
  std::string waited_for_;
  double timeout_s_;
  std::optional<HealthCounters> health_;
};

class VersionError : public Error {
 public:
  using Error::Error;
};

class DeviceError : public Error {
 public:
  /// request: the refused message's name; code: the Nak error code (proto::ErrorCode value).
  DeviceError(const std::string& message, std::string request, std::uint16_t code,
              std::uint8_t field_index, std::int32_t detail);
  const std::string& request() const { return request_; }
  std::uint16_t code() const { return code_; }
  std::uint8_t field_index() const { return field_index_; }
  std::int32_t detail() const { return detail_; }

 private:
  std::string request_;
  std::uint16_t code_;
  std::uint8_t field_index_;
  std::int32_t detail_;
};

class FaultError : public Error {
 public:
  FaultError(const std::string& message, std::uint16_t reason) : Error(message), reason_(reason) {}
  /// The latched proto::FaultReason value.
  std::uint16_t reason() const { return reason_; }

 private:
  std::uint16_t reason_;
};

class ProtocolError : public Error {
 public:
  using Error::Error;
};

class RecordingError : public Error {
 public:
  /// line: 1-based line number in the file, 0 when the problem is not on one line.
  RecordingError(const std::string& file, std::size_t line, const std::string& problem);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string problem_;
};

class DataError : public Error {
 public:
  using Error::Error;
};

class RobotRejectedError : public Error {
 public:
  /// result: the proto::rb::Result rejection code; register_address: the offending register
  /// (rejected_bad_parameter), else 0xFFFF.
  RobotRejectedError(const std::string& message, std::uint16_t result,
                     std::uint16_t register_address = 0xFFFF)
      : Error(message), result_(result), register_address_(register_address) {}
  std::uint16_t result() const { return result_; }
  std::uint16_t register_address() const { return register_address_; }

 private:
  std::uint16_t result_;
  std::uint16_t register_address_;
};

class RobotFaultError : public Error {
 public:
  /// result: the proto::rb::Result the motion ended with (robot_fault, safety_stopped, watchdog).
  RobotFaultError(const std::string& message, std::uint16_t result) : Error(message), result_(result) {}
  std::uint16_t result() const { return result_; }

 private:
  std::uint16_t result_;
};

class FlashError : public Error {
 public:
  /// erased: the flash was erased (in part): the device waits in its ROM bootloader for an image.
  FlashError(const std::string& message, bool erased) : Error(message), erased_(erased) {}
  bool erased() const { return erased_; }

 private:
  bool erased_;
};

class RobotLinkError : public ConnectionError {
 public:
  using ConnectionError::ConnectionError;
};

}  // namespace palp
