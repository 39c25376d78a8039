// SPDX-License-Identifier: Apache-2.0
// Between the SDK's SI view of the robot (robot.hpp) and the register map's blocks
// (protocol/robot-bridge.md): command blocks from SI arguments, status from the status block, and
// the messages a person reads for a rejection or a fault. Pure functions, no I/O.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "palp/protocol/robot_bridge/codec.hpp"
#include "palp/robot.hpp"

namespace palp::detail {

namespace rb = proto::rb;

/// move_lin, move_lin_rel (speed in m/s) or move_ptp (speed as a fraction of the joints'
/// maximum, (0, 1]): x..c from the pose (m -> um and rad -> mdeg, rounded to nearest), speed in
/// um/s or permille. seq is left 0. Throws ConfigError naming the register for a value that does
/// not fit it (not finite, or beyond int32).
rb::Command motion_command(rb::CommandCode code, const Pose& pose, double speed);
rb::Command approach_command(const GuardedApproach& g);
rb::Command tool_command(int id, const Pose& tcp_on_flange);
/// hold or reset_fault: every parameter 0.
rb::Command plain_command(rb::CommandCode code);

/// Runs proto::rb::check_command on c; when the bridge would refuse its parameters, throws
/// ConfigError naming the command, the register (name, address, value, unit); nothing is sent.
void check_command_or_throw(const rb::Command& c);

/// The map's name of a command ("move_lin"), or "#<n>".
std::string command_name(rb::CommandCode code);
/// The map's name of a result ("rejected_busy"), or "#<n>" for a value this SDK does not know.
std::string result_name(rb::Result r);
/// "robot bridge rejected move_lin (seq 7): rejected_unreachable — the target is outside the
/// workspace or joint limits"; for rejected_bad_parameter it names the register at detail.
std::string rejection_text(rb::CommandCode code, std::uint16_t seq, rb::Result r, std::uint16_t detail);
/// "robot bridge: move_lin (seq 7) ended with robot_fault — a robot error ended the motion;
/// state is faulted"
std::string fault_text(rb::CommandCode code, std::uint16_t seq, rb::Result r);
/// The name of the command block's register at address ("speed"), or "#<address>".
std::string command_register_name(std::uint16_t address);

Pose pose_from_registers(rb::i32 x_um, rb::i32 y_um, rb::i32 z_um, rb::i32 a_mdeg, rb::i32 b_mdeg,
                         rb::i32 c_mdeg);
/// Decodes the identification block (the first Identification::kLength registers) and checks
/// it (robot-bridge.md §5.1): another magic or map major is a VersionError that names both and
/// what to do; block addresses or lengths this SDK cannot use are a ProtocolError.
rb::Identification check_identification(std::span<const std::uint16_t> regs, const std::string& uri);
/// Decodes a status block's first StatusBlock::kLength registers; an enumeration value this SDK
/// does not know is a ProtocolError naming the register and the number (§9.4: never guessed).
rb::StatusBlock decode_status(std::span<const std::uint16_t> regs, const std::string& uri);
/// Decodes the host control block.
rb::HostControl decode_control(std::span<const std::uint16_t> regs, const std::string& uri);

/// The status block in SI: latched pose and force only when their status bits say valid.
RobotStatus status_from_block(const rb::StatusBlock& s);

}  // namespace palp::detail
