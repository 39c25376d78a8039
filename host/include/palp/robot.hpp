// SPDX-License-Identifier: Apache-2.0
// palp::Robot: the arm that carries the probe, reached through a robot bridge.
//
// The interface is what an experiment needs from an arm (move, guarded approach, stop, pose,
// faults); the first implementation speaks Modbus TCP (libmodbus) to the bridge application on
// a KUKA Sunrise controller, or to palp-sim's emulator of it, with the register map of
// protocol/robot-bridge.md. A second backend implements the same interface.
//
//   auto robot = palp::connect_robot("modbus://172.31.1.147:30005");  // checks magic + version
//   robot->set_tool(1, probe_tcp);                                      // the probe tip
//   robot->move_lin(above_point, 0.02);                                 // 20 mm/s, waits
//   palp::GuardedApproach g;                                            // tool +z, host stop +
//   g.speed_m_per_s = 1e-3; g.max_travel_m = 0.01; g.digital_input = 1; //   the probe's line
//   auto motion = robot->start_guarded_approach(g);
//   ... probe.wait_contact(...) ...; robot->stop();                     // waits until stationary
//   palp::MotionResult r = robot->wait(motion, 2s);                     // guard_fired, latched
//
// Units: SI (m, rad, m/s, N, s). Poses are the active tool's TCP in the robot's base frame, as
// KUKA gives them: x, y, z, then A, B, C, the ZYX Euler angles (A about z, B about the new y, C
// about the newest x).
//
// Threads: every method may be called from any thread. The Modbus implementation has one owner
// thread for its libmodbus context (which is not thread-safe); it keeps the host heartbeat going
// every watchdog/4 while the Robot lives, polls the status block, and after a response timeout
// closes and reconnects (a late reply would otherwise shift every later transaction), then
// retries a command with the same sequence number so it can never run twice.
//
// Errors (error.hpp): RobotRejectedError (the bridge refused a command: its result code and, for
// a bad parameter, the register), RobotLinkError (the bridge is unreachable or its heartbeat
// stopped), RobotFaultError (the robot faulted or was safety-stopped during a motion),
// TimeoutError (a motion did not finish in time), ConfigError (bad URI or argument), VersionError
// (not a palp bridge, or another major version of the map).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "palp/pose.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"

namespace palp {

/// Who the bridge is (the identification block) and how it was reached.
struct RobotInfo {
  std::string uri;                 ///< "modbus://host:port"
  std::uint16_t map_major = 0, map_minor = 0;
};

/// One status snapshot of the bridge, in SI.
struct RobotStatus {
  proto::rb::RobotState state = proto::rb::RobotState::not_ready;
  std::uint16_t status_bits = 0;        ///< proto::rb::StatusBit bits
  std::uint16_t heartbeat = 0;          ///< the bridge's cycle counter
  std::uint16_t ack_seq = 0, done_seq = 0;
  proto::rb::Result ack_result = proto::rb::Result::none;
  proto::rb::Result result = proto::rb::Result::none;  ///< how done_seq finished
  std::uint16_t guard_fired = 0;        ///< proto::rb::GuardSource bits of done_seq's approach
  std::uint16_t stop_seen = 0;          ///< the last stop_request value the bridge acted on
  int tool = 0;                         ///< active tool id (0: flange)
  double robot_time_s = 0.0;            ///< the bridge's clock
  Pose pose;                            ///< actual TCP
  std::optional<Pose> latched;          ///< pose at the last stop or guard, when valid
  std::optional<double> force_N;        ///< external force along the approach axis, when valid
  std::array<double, 7> joints_rad{};
  bool has(proto::rb::StatusBit b) const { return (status_bits & proto::rb::bit(b)) != 0; }
};

/// A guarded approach: a linear motion along one axis until a guard fires or max travel.
struct GuardedApproach {
  proto::rb::Axis axis = proto::rb::Axis::tool_z;
  double speed_m_per_s = 1e-3;
  double max_travel_m = 10e-3;          ///< signed: its sign is the direction along the axis
  bool guard_host_stop = true;          ///< a stop() ends the approach as a guard
  int digital_input = 0;                ///< 1..16: the wired input (the probe's contact line); 0: none
  std::optional<double> force_threshold_N;  ///< the arm's own force guard; none: not armed
};

/// How a motion ended.
struct MotionResult {
  std::uint16_t seq = 0;
  proto::rb::Result result = proto::rb::Result::none;  ///< done, guard_fired, max_travel, stopped, ...
  std::uint16_t guard_fired = 0;        ///< GuardSource bits, for guard_fired
  std::optional<Pose> latched;          ///< the pose when the stop or guard was taken
  Pose final_pose;                      ///< where the arm came to rest
};

/// A motion started and not yet waited for.
struct MotionHandle {
  std::uint16_t seq = 0;
};

struct RobotOptions {
  std::chrono::milliseconds response_timeout{500};   ///< per Modbus request (map §9.1)
  std::chrono::milliseconds watchdog{500};           ///< written to watchdog_ms after connect
  std::chrono::milliseconds status_period{10};       ///< status block poll while a caller waits
  std::chrono::milliseconds reconnect_for{3000};     ///< give up (RobotLinkError) after this long
};

class Robot {
 public:
  virtual ~Robot() = default;

  virtual const RobotInfo& info() const = 0;
  /// A fresh status snapshot (one read of the status block).
  virtual RobotStatus status() = 0;
  Pose pose() { return status().pose; }

  // --- motions: start returns once the bridge accepted (RobotRejectedError otherwise) --------
  virtual MotionHandle start_move_lin(const Pose& target, double speed_m_per_s) = 0;
  /// An offset in the active tool's frame.
  virtual MotionHandle start_move_lin_rel(const Pose& offset, double speed_m_per_s) = 0;
  /// speed_fraction: of the joints' maximum speed, (0, 1].
  virtual MotionHandle start_move_ptp(const Pose& target, double speed_fraction) = 0;
  virtual MotionHandle start_guarded_approach(const GuardedApproach& g) = 0;
  /// Waits for that motion to finish and returns how. Throws TimeoutError, RobotLinkError, and
  /// RobotFaultError when it ended by robot_fault or safety_stopped.
  virtual MotionResult wait(MotionHandle motion, std::chrono::milliseconds timeout) = 0;

  MotionResult move_lin(const Pose& target, double speed_m_per_s,
                        std::chrono::milliseconds timeout = std::chrono::minutes(2)) {
    return wait(start_move_lin(target, speed_m_per_s), timeout);
  }
  MotionResult move_lin_rel(const Pose& offset, double speed_m_per_s,
                            std::chrono::milliseconds timeout = std::chrono::minutes(2)) {
    return wait(start_move_lin_rel(offset, speed_m_per_s), timeout);
  }

  /// Stop now (any change of stop_request): returns once the arm is stationary (stop_seen), with
  /// the status then; its latched pose is where the stop was taken.
  virtual RobotStatus stop(std::chrono::milliseconds timeout = std::chrono::seconds(2)) = 0;
  /// End any motion and hold; waits for done.
  virtual void hold(std::chrono::milliseconds timeout = std::chrono::seconds(2)) = 0;
  /// Make tool id (1..15) active with its TCP frame relative to the flange.
  virtual void set_tool(int id, const Pose& tcp_on_flange) = 0;
  /// Acknowledge a robot error (faulted -> idle).
  virtual void reset_fault() = 0;
};

/// Connects to a robot bridge: "modbus://host[:port]" (port 30005 by default). Reads and checks
/// the identification block (magic "PALP", map major), then the control and status blocks, and
/// starts the heartbeat. Throws ConfigError, RobotLinkError, VersionError.
std::unique_ptr<Robot> connect_robot(const std::string& uri, RobotOptions options = {});

}  // namespace palp
