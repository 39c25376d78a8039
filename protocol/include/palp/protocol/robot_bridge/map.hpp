// SPDX-License-Identifier: Apache-2.0
// THE register map of the KUKA robot bridge (protocol/robot-bridge.md): defined here once, as
// X-macros. The block structs, their encoders and decoders (codec.hpp), the register tables
// the tests compare with robot-bridge.md, and the emulator's and the SDK's views of the map are
// all expanded from these lists. Change the map only here, then robot-bridge.md and
// protocol/vectors/robot_bridge.txt (the tests name what differs). Rules (robot-bridge.md §9):
//   - a released address, type, unit or enum value never changes within a major;
//   - a minor version may add enum values, status bits and registers at the *end* of a block.
//
// Enumerations: PALP_RB_ENUMS lists them X(Name, doc); PALP_RB_ENUM_<Name> their values
//               E(name, value, doc). Every enum travels as one u16 register.
// Blocks:       B(Name, address, access, doc); access "R" (robot writes, host reads) or
//               "RW" (host writes, robot reads; the host may read it back).
// Registers:    F(type, name, unit, doc); type u16 (1 register), i32 or u32 (2 registers,
//               high word first) or an enum name (1 register). unit: um, mdeg, um/s, mN, ms, or
//               "" for counters, codes and bit sets.
//
// Freestanding: no heap, no exceptions, no RTTI.
#pragma once

#define PALP_RB_MAP_MAJOR 1
#define PALP_RB_MAP_MINOR 0

#define PALP_RB_ENUMS(X)                                                         \
  X(RobotState, "The bridge's view of the robot (status register `state`).")     \
  X(StatusBit, "Bit numbers of the status register `status_bits`.")              \
  X(CommandCode, "What the command block asks for (command register `code`).")   \
  X(Axis, "The approach axis of a guarded approach.")                            \
  X(GuardSource, "Bit numbers of `guard_sources` (command) and `guard_fired` (status).") \
  X(Result, "How a command ended, or why it was rejected (status register `result`).")

#define PALP_RB_ENUM_RobotState(E)                                                               \
  E(not_ready, 0, "The bridge runs but the robot cannot move (drives off, wrong mode, starting).") \
  E(idle, 1, "Ready and stationary; a motion command is accepted.")                              \
  E(moving, 2, "A motion command is being carried out.")                                         \
  E(faulted, 3, "A robot error stopped the arm; only reset_fault is accepted.")                   \
  E(safety_stop, 4, "The safety controller stopped the arm (E-stop, protective stop); cleared at the robot, not by the host.")

#define PALP_RB_ENUM_StatusBit(E)                                                       \
  E(drives_enabled, 0, "The drives are on.")                                            \
  E(automatic_mode, 1, "The controller is in AUT mode (else T1/T2/CRR).")               \
  E(host_heartbeat_ok, 2, "The host heartbeat changed within watchdog_ms.")             \
  E(watchdog_tripped, 3, "A stale host heartbeat stopped a motion; cleared by the next accepted command.") \
  E(latched_pose_valid, 4, "latched_* hold the pose of the last stop or guard.")        \
  E(force_valid, 5, "force_mN is a valid measurement.")                                 \
  E(tool_set, 6, "A set_tool command defined the active tool.")

#define PALP_RB_ENUM_CommandCode(E)                                                 \
  E(none, 0, "No command (the block's value at start-up).")                         \
  E(move_lin, 1, "Linear motion to an absolute pose in the base frame.")            \
  E(move_lin_rel, 2, "Linear motion by an offset in the active tool frame.")        \
  E(move_ptp, 3, "Joint-interpolated motion to an absolute pose in the base frame.") \
  E(guarded_approach, 4, "Linear motion along one axis until a guard fires or max travel.") \
  E(hold, 5, "End any motion and hold the current pose.")                           \
  E(set_tool, 6, "Define the active tool: its id and TCP frame on the flange.")     \
  E(reset_fault, 7, "Acknowledge a robot error and return to idle.")

#define PALP_RB_ENUM_Axis(E)                                 \
  E(none, 0, "No axis (every command but guarded_approach).") \
  E(tool_x, 1, "The active tool's x axis.")                  \
  E(tool_y, 2, "The active tool's y axis.")                  \
  E(tool_z, 3, "The active tool's z axis (the probe's approach axis).") \
  E(base_x, 4, "The base frame's x axis.")                   \
  E(base_y, 5, "The base frame's y axis.")                   \
  E(base_z, 6, "The base frame's z axis.")

#define PALP_RB_ENUM_GuardSource(E)                                                      \
  E(host_stop, 0, "A change of the host's stop_request ends the approach as a guard.")   \
  E(digital_input, 1, "The wired digital input `digital_input` going high.")             \
  E(force, 2, "The external force along the axis reaching force_threshold_mN.")

#define PALP_RB_ENUM_Result(E)                                                           \
  E(none, 0, "No command taken or finished yet.")                                           \
  E(done, 1, "Carried out: the target was reached (hold, set_tool, reset_fault: done).") \
  E(guard_fired, 2, "A guarded approach stopped on a guard; guard_fired names it, latched_* hold the pose.") \
  E(max_travel, 3, "A guarded approach travelled max_travel_um without a guard firing.")  \
  E(stopped, 4, "A host stop request ended the motion; latched_* hold the pose.")        \
  E(watchdog, 5, "The host heartbeat went stale during the motion; the arm was stopped.") \
  E(robot_fault, 6, "A robot error ended the motion; state is faulted.")                 \
  E(safety_stopped, 7, "The safety controller ended the motion.")                        \
  E(superseded, 8, "A hold command ended the motion.")                                   \
  E(accepted, 9, "ack_result only: the command was accepted and is carried out.")       \
  E(rejected_unknown_command, 32, "Rejected: code is not a known command.")              \
  E(rejected_bad_parameter, 33, "Rejected: a parameter is out of range or not zero when unused; result_detail is its address.") \
  E(rejected_busy, 34, "Rejected: a motion is in progress (send hold or a stop first).") \
  E(rejected_not_ready, 35, "Rejected: state is not_ready or safety_stop.")              \
  E(rejected_faulted, 36, "Rejected: state is faulted; only reset_fault is accepted.")   \
  E(rejected_unreachable, 37, "Rejected: the target is outside the workspace or joint limits.") \
  E(rejected_heartbeat_stale, 38, "Rejected: a motion was asked for while the host heartbeat is stale.")

// ---------------------------------------------------------------------------------------------
// Blocks. Each fits one Modbus request (FC3 reads <= 125 registers, FC16 writes <= 123).

#define PALP_RB_BLOCKS(B)                                                                      \
  B(Identification, 0, "R", "Who the bridge is: read first, checked before anything else.")   \
  B(StatusBlock, 100, "R", "Robot -> host: the robot's state, one consistent snapshot per read.") \
  B(HostControl, 200, "RW", "Host -> robot: heartbeat, stop request, watchdog time.")          \
  B(Command, 300, "RW", "Host -> robot: one command, written whole in one request, committed by a new seq.")

#define PALP_RB_FIELDS_Identification(F)                                          \
  F(u32, magic, "", "0x50414C50, ASCII 'PALP' (registers 0x5041 0x4C50).")        \
  F(u16, map_major, "", "Map major version: 1.")                                  \
  F(u16, map_minor, "", "Map minor version: 0.")                                  \
  F(u16, status_address, "", "Address of the status block: 100.")                 \
  F(u16, status_length, "", "Registers in the status block (53 in 1.0).")         \
  F(u16, control_address, "", "Address of the host control block: 200.")          \
  F(u16, control_length, "", "Registers in the host control block (3 in 1.0).")   \
  F(u16, command_address, "", "Address of the command block: 300.")               \
  F(u16, command_length, "", "Registers in the command block (24 in 1.0).")

#define PALP_RB_FIELDS_StatusBlock(F)                                                          \
  F(u16, heartbeat, "", "Robot heartbeat: +1 (mod 65536) every bridge cycle.")                 \
  F(RobotState, state, "", "RobotState.")                                                      \
  F(u16, status_bits, "", "StatusBit bits.")                                                  \
  F(u16, ack_seq, "", "seq of the last command taken, accepted or rejected.")                 \
  F(Result, ack_result, "", "accepted, or why ack_seq was rejected.")                          \
  F(u16, reject_detail, "", "ack_result rejected_bad_parameter: the offending register's address; else 0.") \
  F(u16, done_seq, "", "seq of the last accepted command that finished.")                      \
  F(Result, result, "", "How done_seq finished.")                                              \
  F(u16, guard_fired, "", "GuardSource bits that ended done_seq's approach; else 0.")          \
  F(u16, stop_seen, "", "The last stop_request value the bridge acted on.")                    \
  F(u16, tool, "", "Active tool id (0: flange).")                                              \
  F(u32, robot_time_ms, "ms", "Bridge clock when this snapshot was taken (wraps after 49.7 days).") \
  F(i32, x_um, "um", "Actual TCP x in the base frame.")                                        \
  F(i32, y_um, "um", "Actual TCP y.")                                                          \
  F(i32, z_um, "um", "Actual TCP z.")                                                          \
  F(i32, a_mdeg, "mdeg", "Actual TCP orientation A (KUKA ZYX Euler: A about z).")              \
  F(i32, b_mdeg, "mdeg", "Actual TCP orientation B (about y').")                               \
  F(i32, c_mdeg, "mdeg", "Actual TCP orientation C (about x'').")                              \
  F(i32, latched_x_um, "um", "TCP x latched at the last stop or guard.")                       \
  F(i32, latched_y_um, "um", "Latched y.")                                                     \
  F(i32, latched_z_um, "um", "Latched z.")                                                     \
  F(i32, latched_a_mdeg, "mdeg", "Latched A.")                                                 \
  F(i32, latched_b_mdeg, "mdeg", "Latched B.")                                                 \
  F(i32, latched_c_mdeg, "mdeg", "Latched C.")                                                 \
  F(i32, force_mN, "mN", "External force along the approach axis, positive against the motion.") \
  F(i32, a1_mdeg, "mdeg", "Joint A1.")                                                         \
  F(i32, a2_mdeg, "mdeg", "Joint A2.")                                                         \
  F(i32, a3_mdeg, "mdeg", "Joint A3.")                                                         \
  F(i32, a4_mdeg, "mdeg", "Joint A4.")                                                         \
  F(i32, a5_mdeg, "mdeg", "Joint A5.")                                                         \
  F(i32, a6_mdeg, "mdeg", "Joint A6.")                                                         \
  F(i32, a7_mdeg, "mdeg", "Joint A7.")

#define PALP_RB_FIELDS_HostControl(F)                                                  \
  F(u16, host_heartbeat, "", "Host heartbeat: the host changes it at least every watchdog_ms / 4.") \
  F(u16, stop_request, "", "Stop counter: any change means stop now.")                 \
  F(u16, watchdog_ms, "ms", "Host heartbeat timeout, 100..10000 (500 until written).")

#define PALP_RB_FIELDS_Command(F)                                                             \
  F(u16, seq, "", "Sequence number 1..65535; a new value commits the block.")                 \
  F(CommandCode, code, "", "CommandCode.")                                                    \
  F(u16, guard_sources, "", "guarded_approach: GuardSource bits, at least one.")              \
  F(Axis, axis, "", "guarded_approach: the axis; the sign of max_travel_um is the direction.") \
  F(u16, digital_input, "", "guarded_approach with the digital_input guard: input 1..16.")     \
  F(u16, tool, "", "set_tool: tool id 1..15.")                                                \
  F(i32, speed, "um/s", "Cartesian TCP speed; move_ptp: joint speed in permille of the maximum.") \
  F(i32, force_threshold_mN, "mN", "guarded_approach with the force guard: threshold, > 0.")  \
  F(i32, max_travel_um, "um", "guarded_approach: signed travel limit along the axis, != 0.")  \
  F(i32, x_um, "um", "Target x (move_lin, move_ptp: base frame; move_lin_rel: tool-frame offset; set_tool: TCP on the flange).") \
  F(i32, y_um, "um", "Target y.")                                                             \
  F(i32, z_um, "um", "Target z.")                                                             \
  F(i32, a_mdeg, "mdeg", "Target A.")                                                         \
  F(i32, b_mdeg, "mdeg", "Target B.")                                                         \
  F(i32, c_mdeg, "mdeg", "Target C.")
