// SPDX-License-Identifier: Apache-2.0
// RobotBridge: the robot-bridge application of protocol/robot-bridge.md as palp-sim emulates
// it, without sockets. It holds the register map, runs the bridge's cycle (§8.3) in virtual time
// on a RobotArm, and answers Modbus-level accesses (§3) with the exception code to send.
//
//   - Time: advance(dt, wall) steps the arm by dt of virtual time and runs one cycle every
//     cycle period (1 ms virtual by default). robot_time_ms is virtual time. The host-heartbeat
//     watchdog counts on wall time (DESIGN: watchdogs count on their own clock).
//   - Writes are stored at once (a read-back shows them) and handed to the cycle whole, at the
//     first cycle at or after their apply time (palp-sim delays a host's reaction to a held
//     contact event by the reaction latency, like device bytes).
//   - A stop, a guard, a stale heartbeat, a dropped connection or a robot fault brake the arm on
//     its path (RobotArm::stop); the command finishes, with result and done_seq together, once
//     the arm is stationary. The pose is latched in the cycle that takes the stop or the guard.
//   - Inputs from the world: the digital inputs (bit k-1 = input k) and the external force on
//     the TCP in the base frame; force_mN is its component against the approach direction
//     (the last guarded approach's, tool +z before any) plus seeded Gaussian noise.
//   - Joints are not modelled: a1..a7 read 0. The robot is always ready (drives on, AUT).
//
// Not thread-safe: palp-sim drives it from its one loop.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "palp/plant/robot_arm.hpp"
#include "palp/protocol/robot_bridge/check.hpp"

namespace palp::sim {

namespace rb = proto::rb;

struct RobotBridgeOptions {
  double cycle_ms = 1.0;         ///< the bridge's cycle period, virtual time
  double force_noise_N = 0.05;   ///< sigma of the noise on force_mN
  std::uint64_t seed = 1;        ///< noise seed
};

/// Modbus exception codes the bridge answers with (§9.3); 0: served.
enum class ModbusException : std::uint8_t {
  none = 0,
  illegal_function = 1,
  illegal_data_address = 2,
  illegal_data_value = 3,
  server_device_failure = 4,
};

class RobotBridge {
 public:
  explicit RobotBridge(plant::RobotArm& arm, RobotBridgeOptions options = {});

  // --- Modbus access (§3, §9.3) --------------------------------------------------------
  /// FC3: count registers from address into out. Inside one block, 1..125 registers.
  ModbusException read(std::uint16_t address, std::uint16_t count, std::uint16_t* out) const;
  /// FC16 (single = false) or FC6 (single = true, one register): writes only into the RW
  /// blocks, the command block only whole (300, 24 registers), watchdog_ms in 100..10000.
  /// The write takes effect at the first cycle at or after apply_at_s (virtual time).
  ModbusException write(std::uint16_t address, std::span<const std::uint16_t> regs,
                        bool single, double apply_at_s);
  ModbusException write(std::uint16_t address, std::span<const std::uint16_t> regs, bool single) {
    return write(address, regs, single, time_s_);
  }
  /// The exception write() would answer, without writing.
  ModbusException check_write(std::uint16_t address, std::span<const std::uint16_t> regs,
                              bool single) const;
  /// Whether this (valid) write asks the robot to act: it commits a new command seq or changes
  /// stop_request. Such a write is the host's reaction to a held contact event.
  bool is_reaction(std::uint16_t address, std::span<const std::uint16_t> regs) const;

  // --- the world ------------------------------------------------------------------------
  /// Digital inputs as the robot sees them now: bit k-1 is input k (1..16).
  void set_digital_inputs(std::uint16_t bits) { inputs_ = bits; }
  std::uint16_t digital_inputs() const { return inputs_; }
  /// External force on the TCP, N, base frame (valid = false: no measurement).
  void set_external_force(const double f_base_N[3], bool valid = true);
  /// The host's connection closed (§2): a motion is stopped and ends with `watchdog`.
  void connection_closed();

  // --- fault knobs -----------------------------------------------------------------------
  /// The robot heartbeat stops counting (the bridge looks hung).
  void freeze_heartbeat(bool frozen) { heartbeat_frozen_ = frozen; }
  /// The next n committed commands are rejected with `code` (a rejection Result).
  void reject_next(rb::Result code, unsigned n) { reject_code_ = code, reject_left_ = n; }
  /// A robot error: a motion brakes and ends with robot_fault; the state becomes faulted until
  /// reset_fault.
  void inject_fault() { fault_pending_ = true; }

  // --- time -------------------------------------------------------------------------------
  /// Steps the arm by dt_s of virtual time and runs every cycle that falls due; wall_us is the
  /// wall clock (any epoch) for the watchdog.
  void advance(double dt_s, std::uint64_t wall_us);
  /// One bridge cycle now (§8.3).
  void cycle(std::uint64_t wall_us);

  // --- observation -------------------------------------------------------------------------
  const rb::StatusBlock& status() const { return status_; }
  const rb::HostControl& control() const { return control_; }
  double time_s() const { return time_s_; }
  const plant::RobotArm& arm() const { return arm_; }
  struct Counters {
    std::uint64_t cycles = 0, commands = 0, rejected = 0, stops = 0, guards = 0, watchdogs = 0;
  };
  const Counters& counters() const { return counters_; }

 private:
  struct Motion {
    bool active = false;
    std::uint16_t seq = 0;
    rb::CommandCode code = rb::CommandCode::none;
    rb::Command cmd{};
    bool ending = false;  // braking towards its end_result
    rb::Result end_result = rb::Result::none;
    std::uint16_t fired = 0;
  };

  void apply_due_writes();
  void take_stop();
  void take_command(std::uint64_t wall_us, bool stale);
  rb::CommandVerdict verdict(const rb::Command& c, bool stale) const;
  void start(const rb::Command& c);
  void advance_motion();
  void end_motion(rb::Result r, std::uint16_t fired = 0);
  void finish(rb::Result r, std::uint16_t fired = 0);
  void latch();
  void publish(bool stale);
  void publish_force();
  void pose_registers(const plant::Transform& t, rb::i32* xyzabc) const;
  bool direction_of(const rb::Command& c, double d[3]) const;

  plant::RobotArm& arm_;
  RobotBridgeOptions options_;
  std::mt19937_64 rng_;
  double time_s_ = 0.0, next_cycle_s_ = 0.0;

  // what the host wrote (read back at once) and what the cycle has taken
  std::array<std::uint16_t, rb::HostControl::kLength> written_control_{};
  std::array<std::uint16_t, rb::Command::kLength> written_command_{};
  struct PendingWrite {
    std::uint16_t address;
    std::vector<std::uint16_t> regs;
    double apply_at_s;
  };
  std::vector<PendingWrite> pending_;
  rb::HostControl control_{};
  std::array<std::uint16_t, rb::Command::kLength> command_{};

  // bridge state
  rb::StatusBlock status_{};
  std::array<std::uint16_t, rb::StatusBlock::kLength> status_regs_{};
  Motion motion_;
  bool faulted_ = false, fault_pending_ = false, closed_pending_ = false;
  bool watchdog_tripped_ = false, latched_valid_ = false, tool_set_ = false;
  std::uint16_t stop_acted_ = 0;     // the last stop_request value taken
  std::uint16_t last_heartbeat_ = 0;
  bool heartbeat_seen_ = false;
  std::uint64_t heartbeat_wall_us_ = 0;
  bool wall_started_ = false;
  std::uint16_t inputs_ = 0;
  double force_[3] = {0, 0, 0};
  bool force_valid_ = false;
  double approach_dir_[3] = {0, 0, 0};
  bool approach_set_ = false;
  bool heartbeat_frozen_ = false;
  rb::Result reject_code_ = rb::Result::none;
  unsigned reject_left_ = 0;
  Counters counters_;
};

}  // namespace palp::sim
