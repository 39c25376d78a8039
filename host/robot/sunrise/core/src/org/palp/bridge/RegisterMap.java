// SPDX-License-Identifier: Apache-2.0
// GENERATED from protocol/include/palp/protocol/robot_bridge/map.hpp and check.hpp by
// protocol/tools/palp-rb-constants.cpp. Do not edit: change map.hpp, then run
//   build/release-with-assertions/protocol/palp-rb-constants java --write host/robot/sunrise/core/src/org/palp/bridge/RegisterMap.java
// The test `sunrise_register_map_generated` fails while this file differs from the map.
package org.palp.bridge;

/** The robot bridge's register map 1.0 (protocol/robot-bridge.md): absolute 0-based addresses, enumerations, limits. */
public final class RegisterMap {
  private RegisterMap() {}

  public static final int MAP_MAJOR = 1;
  public static final int MAP_MINOR = 0;
  /** ASCII 'PALP'. */
  public static final int MAGIC = 0x50414c50;
  public static final int DEFAULT_PORT = 30005;
  public static final int MAX_READ_REGISTERS = 125;
  public static final int MAX_WRITE_REGISTERS = 123;
  public static final int DEFAULT_WATCHDOG_MS = 500;
  public static final int MIN_WATCHDOG_MS = 100;
  public static final int MAX_WATCHDOG_MS = 10000;

  // Command parameter limits (robot-bridge.md section 6, check.hpp).
  public static final int MAX_LIN_SPEED_UM_PER_S = 1000000;
  public static final int MAX_APPROACH_SPEED_UM_PER_S = 100000;
  public static final int MAX_PTP_SPEED_PERMILLE = 1000;
  public static final int MAX_APPROACH_TRAVEL_UM = 500000;
  public static final int MAX_FORCE_THRESHOLD_MN = 1000000;
  public static final int MAX_ANGLE_MDEG = 180000;
  public static final int MAX_DIGITAL_INPUT = 16;
  public static final int MAX_TOOL = 15;

  /** The bridge's view of the robot (status register `state`). */
  public static final class RobotState {
    private RobotState() {}
    /** 0: The bridge runs but the robot cannot move (drives off, wrong mode, starting). */
    public static final int NOT_READY = 0;
    /** 1: Ready and stationary; a motion command is accepted. */
    public static final int IDLE = 1;
    /** 2: A motion command is being carried out. */
    public static final int MOVING = 2;
    /** 3: A robot error stopped the arm; only reset_fault is accepted. */
    public static final int FAULTED = 3;
    /** 4: The safety controller stopped the arm (E-stop, protective stop); cleared at the robot, not by the host. */
    public static final int SAFETY_STOP = 4;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "not_ready";
        case 1: return "idle";
        case 2: return "moving";
        case 3: return "faulted";
        case 4: return "safety_stop";
        default: return null;
      }
    }
  }

  /** Bit numbers of the status register `status_bits`. */
  public static final class StatusBit {
    private StatusBit() {}
    /** 0: The drives are on. */
    public static final int DRIVES_ENABLED = 0;
    public static final int DRIVES_ENABLED_MASK = 0x0001;
    /** 1: The controller is in AUT mode (else T1/T2/CRR). */
    public static final int AUTOMATIC_MODE = 1;
    public static final int AUTOMATIC_MODE_MASK = 0x0002;
    /** 2: The host heartbeat changed within watchdog_ms. */
    public static final int HOST_HEARTBEAT_OK = 2;
    public static final int HOST_HEARTBEAT_OK_MASK = 0x0004;
    /** 3: A stale host heartbeat stopped a motion; cleared by the next accepted command. */
    public static final int WATCHDOG_TRIPPED = 3;
    public static final int WATCHDOG_TRIPPED_MASK = 0x0008;
    /** 4: latched_* hold the pose of the last stop or guard. */
    public static final int LATCHED_POSE_VALID = 4;
    public static final int LATCHED_POSE_VALID_MASK = 0x0010;
    /** 5: force_mN is a valid measurement. */
    public static final int FORCE_VALID = 5;
    public static final int FORCE_VALID_MASK = 0x0020;
    /** 6: A set_tool command defined the active tool. */
    public static final int TOOL_SET = 6;
    public static final int TOOL_SET_MASK = 0x0040;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "drives_enabled";
        case 1: return "automatic_mode";
        case 2: return "host_heartbeat_ok";
        case 3: return "watchdog_tripped";
        case 4: return "latched_pose_valid";
        case 5: return "force_valid";
        case 6: return "tool_set";
        default: return null;
      }
    }

    /** Every bit this map knows. */
    public static final int KNOWN_MASK = 0x007F;
  }

  /** What the command block asks for (command register `code`). */
  public static final class CommandCode {
    private CommandCode() {}
    /** 0: No command (the block's value at start-up). */
    public static final int NONE = 0;
    /** 1: Linear motion to an absolute pose in the base frame. */
    public static final int MOVE_LIN = 1;
    /** 2: Linear motion by an offset in the active tool frame. */
    public static final int MOVE_LIN_REL = 2;
    /** 3: Joint-interpolated motion to an absolute pose in the base frame. */
    public static final int MOVE_PTP = 3;
    /** 4: Linear motion along one axis until a guard fires or max travel. */
    public static final int GUARDED_APPROACH = 4;
    /** 5: End any motion and hold the current pose. */
    public static final int HOLD = 5;
    /** 6: Define the active tool: its id and TCP frame on the flange. */
    public static final int SET_TOOL = 6;
    /** 7: Acknowledge a robot error and return to idle. */
    public static final int RESET_FAULT = 7;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "none";
        case 1: return "move_lin";
        case 2: return "move_lin_rel";
        case 3: return "move_ptp";
        case 4: return "guarded_approach";
        case 5: return "hold";
        case 6: return "set_tool";
        case 7: return "reset_fault";
        default: return null;
      }
    }
  }

  /** The approach axis of a guarded approach. */
  public static final class Axis {
    private Axis() {}
    /** 0: No axis (every command but guarded_approach). */
    public static final int NONE = 0;
    /** 1: The active tool's x axis. */
    public static final int TOOL_X = 1;
    /** 2: The active tool's y axis. */
    public static final int TOOL_Y = 2;
    /** 3: The active tool's z axis (the probe's approach axis). */
    public static final int TOOL_Z = 3;
    /** 4: The base frame's x axis. */
    public static final int BASE_X = 4;
    /** 5: The base frame's y axis. */
    public static final int BASE_Y = 5;
    /** 6: The base frame's z axis. */
    public static final int BASE_Z = 6;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "none";
        case 1: return "tool_x";
        case 2: return "tool_y";
        case 3: return "tool_z";
        case 4: return "base_x";
        case 5: return "base_y";
        case 6: return "base_z";
        default: return null;
      }
    }
  }

  /** Bit numbers of `guard_sources` (command) and `guard_fired` (status). */
  public static final class GuardSource {
    private GuardSource() {}
    /** 0: A change of the host's stop_request ends the approach as a guard. */
    public static final int HOST_STOP = 0;
    public static final int HOST_STOP_MASK = 0x0001;
    /** 1: The wired digital input `digital_input` going high. */
    public static final int DIGITAL_INPUT = 1;
    public static final int DIGITAL_INPUT_MASK = 0x0002;
    /** 2: The external force along the axis reaching force_threshold_mN. */
    public static final int FORCE = 2;
    public static final int FORCE_MASK = 0x0004;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "host_stop";
        case 1: return "digital_input";
        case 2: return "force";
        default: return null;
      }
    }

    /** Every bit this map knows. */
    public static final int KNOWN_MASK = 0x0007;
  }

  /** How a command ended, or why it was rejected (status register `result`). */
  public static final class Result {
    private Result() {}
    /** 0: No command taken or finished yet. */
    public static final int NONE = 0;
    /** 1: Carried out: the target was reached (hold, set_tool, reset_fault: done). */
    public static final int DONE = 1;
    /** 2: A guarded approach stopped on a guard; guard_fired names it, latched_* hold the pose. */
    public static final int GUARD_FIRED = 2;
    /** 3: A guarded approach travelled max_travel_um without a guard firing. */
    public static final int MAX_TRAVEL = 3;
    /** 4: A host stop request ended the motion; latched_* hold the pose. */
    public static final int STOPPED = 4;
    /** 5: The host heartbeat went stale during the motion; the arm was stopped. */
    public static final int WATCHDOG = 5;
    /** 6: A robot error ended the motion; state is faulted. */
    public static final int ROBOT_FAULT = 6;
    /** 7: The safety controller ended the motion. */
    public static final int SAFETY_STOPPED = 7;
    /** 8: A hold command ended the motion. */
    public static final int SUPERSEDED = 8;
    /** 9: ack_result only: the command was accepted and is carried out. */
    public static final int ACCEPTED = 9;
    /** 32: Rejected: code is not a known command. */
    public static final int REJECTED_UNKNOWN_COMMAND = 32;
    /** 33: Rejected: a parameter is out of range or not zero when unused; result_detail is its address. */
    public static final int REJECTED_BAD_PARAMETER = 33;
    /** 34: Rejected: a motion is in progress (send hold or a stop first). */
    public static final int REJECTED_BUSY = 34;
    /** 35: Rejected: state is not_ready or safety_stop. */
    public static final int REJECTED_NOT_READY = 35;
    /** 36: Rejected: state is faulted; only reset_fault is accepted. */
    public static final int REJECTED_FAULTED = 36;
    /** 37: Rejected: the target is outside the workspace or joint limits. */
    public static final int REJECTED_UNREACHABLE = 37;
    /** 38: Rejected: a motion was asked for while the host heartbeat is stale. */
    public static final int REJECTED_HEARTBEAT_STALE = 38;

    /** The map's name of a value, or null for a value this map does not know. */
    public static String name(int value) {
      switch (value) {
        case 0: return "none";
        case 1: return "done";
        case 2: return "guard_fired";
        case 3: return "max_travel";
        case 4: return "stopped";
        case 5: return "watchdog";
        case 6: return "robot_fault";
        case 7: return "safety_stopped";
        case 8: return "superseded";
        case 9: return "accepted";
        case 32: return "rejected_unknown_command";
        case 33: return "rejected_bad_parameter";
        case 34: return "rejected_busy";
        case 35: return "rejected_not_ready";
        case 36: return "rejected_faulted";
        case 37: return "rejected_unreachable";
        case 38: return "rejected_heartbeat_stale";
        default: return null;
      }
    }
  }

  /** Who the bridge is: read first, checked before anything else. Access R. */
  public static final class Identification {
    private Identification() {}
    public static final int ADDRESS = 0;
    public static final int LENGTH = 10;
    /** True when the host writes this block (access RW). */
    public static final boolean HOST_WRITES = false;
    /** u32, address 0-1: 0x50414C50, ASCII 'PALP' (registers 0x5041 0x4C50). */
    public static final int MAGIC = 0;
    /** u16, address 2: Map major version: 1. */
    public static final int MAP_MAJOR = 2;
    /** u16, address 3: Map minor version: 0. */
    public static final int MAP_MINOR = 3;
    /** u16, address 4: Address of the status block: 100. */
    public static final int STATUS_ADDRESS = 4;
    /** u16, address 5: Registers in the status block (53 in 1.0). */
    public static final int STATUS_LENGTH = 5;
    /** u16, address 6: Address of the host control block: 200. */
    public static final int CONTROL_ADDRESS = 6;
    /** u16, address 7: Registers in the host control block (3 in 1.0). */
    public static final int CONTROL_LENGTH = 7;
    /** u16, address 8: Address of the command block: 300. */
    public static final int COMMAND_ADDRESS = 8;
    /** u16, address 9: Registers in the command block (24 in 1.0). */
    public static final int COMMAND_LENGTH = 9;

    /** The register's name at an absolute address of this block (the first of a pair), or null. */
    public static String registerName(int address) {
      switch (address) {
        case 0: return "magic";
        case 2: return "map_major";
        case 3: return "map_minor";
        case 4: return "status_address";
        case 5: return "status_length";
        case 6: return "control_address";
        case 7: return "control_length";
        case 8: return "command_address";
        case 9: return "command_length";
        default: return null;
      }
    }

    /** 2 for a register that starts an i32/u32 pair, 1 for u16 and enums, 0 elsewhere. */
    public static int width(int address) {
      switch (address) {
        case 0:
          return 2;
        default:
          return registerName(address) != null ? 1 : 0;
      }
    }
  }

  /** Robot -> host: the robot's state, one consistent snapshot per read. Access R. */
  public static final class StatusBlock {
    private StatusBlock() {}
    public static final int ADDRESS = 100;
    public static final int LENGTH = 53;
    /** True when the host writes this block (access RW). */
    public static final boolean HOST_WRITES = false;
    /** u16, address 100: Robot heartbeat: +1 (mod 65536) every bridge cycle. */
    public static final int HEARTBEAT = 100;
    /** RobotState, address 101: RobotState. */
    public static final int STATE = 101;
    /** u16, address 102: StatusBit bits. */
    public static final int STATUS_BITS = 102;
    /** u16, address 103: seq of the last command taken, accepted or rejected. */
    public static final int ACK_SEQ = 103;
    /** Result, address 104: accepted, or why ack_seq was rejected. */
    public static final int ACK_RESULT = 104;
    /** u16, address 105: ack_result rejected_bad_parameter: the offending register's address; else 0. */
    public static final int REJECT_DETAIL = 105;
    /** u16, address 106: seq of the last accepted command that finished. */
    public static final int DONE_SEQ = 106;
    /** Result, address 107: How done_seq finished. */
    public static final int RESULT = 107;
    /** u16, address 108: GuardSource bits that ended done_seq's approach; else 0. */
    public static final int GUARD_FIRED = 108;
    /** u16, address 109: The last stop_request value the bridge acted on. */
    public static final int STOP_SEEN = 109;
    /** u16, address 110: Active tool id (0: flange). */
    public static final int TOOL = 110;
    /** u32 [ms], address 111-112: Bridge clock when this snapshot was taken (wraps after 49.7 days). */
    public static final int ROBOT_TIME_MS = 111;
    /** i32 [um], address 113-114: Actual TCP x in the base frame. */
    public static final int X_UM = 113;
    /** i32 [um], address 115-116: Actual TCP y. */
    public static final int Y_UM = 115;
    /** i32 [um], address 117-118: Actual TCP z. */
    public static final int Z_UM = 117;
    /** i32 [mdeg], address 119-120: Actual TCP orientation A (KUKA ZYX Euler: A about z). */
    public static final int A_MDEG = 119;
    /** i32 [mdeg], address 121-122: Actual TCP orientation B (about y'). */
    public static final int B_MDEG = 121;
    /** i32 [mdeg], address 123-124: Actual TCP orientation C (about x''). */
    public static final int C_MDEG = 123;
    /** i32 [um], address 125-126: TCP x latched at the last stop or guard. */
    public static final int LATCHED_X_UM = 125;
    /** i32 [um], address 127-128: Latched y. */
    public static final int LATCHED_Y_UM = 127;
    /** i32 [um], address 129-130: Latched z. */
    public static final int LATCHED_Z_UM = 129;
    /** i32 [mdeg], address 131-132: Latched A. */
    public static final int LATCHED_A_MDEG = 131;
    /** i32 [mdeg], address 133-134: Latched B. */
    public static final int LATCHED_B_MDEG = 133;
    /** i32 [mdeg], address 135-136: Latched C. */
    public static final int LATCHED_C_MDEG = 135;
    /** i32 [mN], address 137-138: External force along the approach axis, positive against the motion. */
    public static final int FORCE_MN = 137;
    /** i32 [mdeg], address 139-140: Joint A1. */
    public static final int A1_MDEG = 139;
    /** i32 [mdeg], address 141-142: Joint A2. */
    public static final int A2_MDEG = 141;
    /** i32 [mdeg], address 143-144: Joint A3. */
    public static final int A3_MDEG = 143;
    /** i32 [mdeg], address 145-146: Joint A4. */
    public static final int A4_MDEG = 145;
    /** i32 [mdeg], address 147-148: Joint A5. */
    public static final int A5_MDEG = 147;
    /** i32 [mdeg], address 149-150: Joint A6. */
    public static final int A6_MDEG = 149;
    /** i32 [mdeg], address 151-152: Joint A7. */
    public static final int A7_MDEG = 151;

    /** The register's name at an absolute address of this block (the first of a pair), or null. */
    public static String registerName(int address) {
      switch (address) {
        case 100: return "heartbeat";
        case 101: return "state";
        case 102: return "status_bits";
        case 103: return "ack_seq";
        case 104: return "ack_result";
        case 105: return "reject_detail";
        case 106: return "done_seq";
        case 107: return "result";
        case 108: return "guard_fired";
        case 109: return "stop_seen";
        case 110: return "tool";
        case 111: return "robot_time_ms";
        case 113: return "x_um";
        case 115: return "y_um";
        case 117: return "z_um";
        case 119: return "a_mdeg";
        case 121: return "b_mdeg";
        case 123: return "c_mdeg";
        case 125: return "latched_x_um";
        case 127: return "latched_y_um";
        case 129: return "latched_z_um";
        case 131: return "latched_a_mdeg";
        case 133: return "latched_b_mdeg";
        case 135: return "latched_c_mdeg";
        case 137: return "force_mN";
        case 139: return "a1_mdeg";
        case 141: return "a2_mdeg";
        case 143: return "a3_mdeg";
        case 145: return "a4_mdeg";
        case 147: return "a5_mdeg";
        case 149: return "a6_mdeg";
        case 151: return "a7_mdeg";
        default: return null;
      }
    }

    /** 2 for a register that starts an i32/u32 pair, 1 for u16 and enums, 0 elsewhere. */
    public static int width(int address) {
      switch (address) {
        case 111:
        case 113:
        case 115:
        case 117:
        case 119:
        case 121:
        case 123:
        case 125:
        case 127:
        case 129:
        case 131:
        case 133:
        case 135:
        case 137:
        case 139:
        case 141:
        case 143:
        case 145:
        case 147:
        case 149:
        case 151:
          return 2;
        default:
          return registerName(address) != null ? 1 : 0;
      }
    }
  }

  /** Host -> robot: heartbeat, stop request, watchdog time. Access RW. */
  public static final class HostControl {
    private HostControl() {}
    public static final int ADDRESS = 200;
    public static final int LENGTH = 3;
    /** True when the host writes this block (access RW). */
    public static final boolean HOST_WRITES = true;
    /** u16, address 200: Host heartbeat: the host changes it at least every watchdog_ms / 4. */
    public static final int HOST_HEARTBEAT = 200;
    /** u16, address 201: Stop counter: any change means stop now. */
    public static final int STOP_REQUEST = 201;
    /** u16 [ms], address 202: Host heartbeat timeout, 100..10000 (500 until written). */
    public static final int WATCHDOG_MS = 202;

    /** The register's name at an absolute address of this block (the first of a pair), or null. */
    public static String registerName(int address) {
      switch (address) {
        case 200: return "host_heartbeat";
        case 201: return "stop_request";
        case 202: return "watchdog_ms";
        default: return null;
      }
    }

    /** 2 for a register that starts an i32/u32 pair, 1 for u16 and enums, 0 elsewhere. */
    public static int width(int address) {
      switch (address) {
        default:
          return registerName(address) != null ? 1 : 0;
      }
    }
  }

  /** Host -> robot: one command, written whole in one request, committed by a new seq. Access RW. */
  public static final class Command {
    private Command() {}
    public static final int ADDRESS = 300;
    public static final int LENGTH = 24;
    /** True when the host writes this block (access RW). */
    public static final boolean HOST_WRITES = true;
    /** u16, address 300: Sequence number 1..65535; a new value commits the block. */
    public static final int SEQ = 300;
    /** CommandCode, address 301: CommandCode. */
    public static final int CODE = 301;
    /** u16, address 302: guarded_approach: GuardSource bits, at least one. */
    public static final int GUARD_SOURCES = 302;
    /** Axis, address 303: guarded_approach: the axis; the sign of max_travel_um is the direction. */
    public static final int AXIS = 303;
    /** u16, address 304: guarded_approach with the digital_input guard: input 1..16. */
    public static final int DIGITAL_INPUT = 304;
    /** u16, address 305: set_tool: tool id 1..15. */
    public static final int TOOL = 305;
    /** i32 [um/s], address 306-307: Cartesian TCP speed; move_ptp: joint speed in permille of the maximum. */
    public static final int SPEED = 306;
    /** i32 [mN], address 308-309: guarded_approach with the force guard: threshold, > 0. */
    public static final int FORCE_THRESHOLD_MN = 308;
    /** i32 [um], address 310-311: guarded_approach: signed travel limit along the axis, != 0. */
    public static final int MAX_TRAVEL_UM = 310;
    /** i32 [um], address 312-313: Target x (move_lin, move_ptp: base frame; move_lin_rel: tool-frame offset; set_tool: TCP on the flange). */
    public static final int X_UM = 312;
    /** i32 [um], address 314-315: Target y. */
    public static final int Y_UM = 314;
    /** i32 [um], address 316-317: Target z. */
    public static final int Z_UM = 316;
    /** i32 [mdeg], address 318-319: Target A. */
    public static final int A_MDEG = 318;
    /** i32 [mdeg], address 320-321: Target B. */
    public static final int B_MDEG = 320;
    /** i32 [mdeg], address 322-323: Target C. */
    public static final int C_MDEG = 322;

    /** The register's name at an absolute address of this block (the first of a pair), or null. */
    public static String registerName(int address) {
      switch (address) {
        case 300: return "seq";
        case 301: return "code";
        case 302: return "guard_sources";
        case 303: return "axis";
        case 304: return "digital_input";
        case 305: return "tool";
        case 306: return "speed";
        case 308: return "force_threshold_mN";
        case 310: return "max_travel_um";
        case 312: return "x_um";
        case 314: return "y_um";
        case 316: return "z_um";
        case 318: return "a_mdeg";
        case 320: return "b_mdeg";
        case 322: return "c_mdeg";
        default: return null;
      }
    }

    /** 2 for a register that starts an i32/u32 pair, 1 for u16 and enums, 0 elsewhere. */
    public static int width(int address) {
      switch (address) {
        case 306:
        case 308:
        case 310:
        case 312:
        case 314:
        case 316:
        case 318:
        case 320:
        case 322:
          return 2;
        default:
          return registerName(address) != null ? 1 : 0;
      }
    }
  }
}
